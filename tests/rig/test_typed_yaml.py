"""parse_yaml, the one reader of YAML text: empty text, text that is not YAML, and YAML past
its limits."""

import dataclasses

import pytest

from tegrasp_drake.rig.typed_yaml import ConfigError, YamlSyntaxError, parse_yaml


def test_empty_text_is_no_data():
    assert parse_yaml("", "the text") is None


def test_text_that_is_not_yaml_is_a_syntax_error_naming_the_source():
    with pytest.raises(YamlSyntaxError, match="^the text: not valid YAML: line 1, column"):
        parse_yaml("note: a: b", "the text")


def test_yaml_past_the_limits_is_a_config_error_but_not_a_syntax_error():
    with pytest.raises(ConfigError, match="key 'a' appears twice") as error:
        parse_yaml("a: 1\na: 2\n", "the text")
    assert not isinstance(error.value, YamlSyntaxError)


def test_an_unquoted_number_in_exponent_notation_is_a_number():
    data = parse_yaml("a: 1e-30\nb: [2E+3, -4e5]\nc: '1e-30'\nd: \"5e3\"\ne: {f: 1e2}\n", "s")
    assert data == {"a": 1e-30, "b": [2000.0, -400000.0], "c": "1e-30", "d": "5e3",
                    "e": {"f": 100.0}}  # quoted: the text the user wrote
    assert parse_yaml("value: 1e-9", "--set") == {"value": 1e-9}


YAML_12_HINT = "numbers are read as YAML 1.2 reads them"


@pytest.mark.parametrize("text", ["1:30", "0b101", "1_000", "+0x10", "'0b101'"])
def test_a_number_only_yaml_11_reads_is_refused_with_the_yaml_12_hint(text):
    from tegrasp_drake.rig.typed_yaml import check_fields
    with pytest.raises(ConfigError, match="field 'count' must be an integer") as error:
        check_fields(parse_yaml(f"count: {text}", "s"), _Counted, "s")
    assert YAML_12_HINT in str(error.value)


@pytest.mark.parametrize("text, hint", [("'12'", "write 12, digits without quotes"),
                                        ("0o8", "")])
def test_text_yaml_11_does_not_read_as_a_number_has_no_yaml_12_hint(text, hint):
    from tegrasp_drake.rig.typed_yaml import check_fields
    with pytest.raises(ConfigError, match="field 'count' must be an integer") as error:
        check_fields(parse_yaml(f"count: {text}", "s"), _Counted, "s")
    assert YAML_12_HINT not in str(error.value) and hint in str(error.value)


@dataclasses.dataclass
class _Counted:
    count: int = 0
