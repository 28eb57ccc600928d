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
