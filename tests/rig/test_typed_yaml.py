"""parse_yaml, the one reader of YAML text: empty text, text that is not YAML, and YAML past
its limits."""

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
