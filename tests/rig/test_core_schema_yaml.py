"""YAML scalars read as YAML 1.2's core schema reads them (rig/core_schema_yaml.py)."""

import math

import pytest

from tegrasp_drake.rig.core_schema_yaml import compose, construct


def _value(text: str):
    return construct(compose(f"v: {text}"))["v"]


@pytest.mark.parametrize("text, value", [
    ("017", 17), ("0o17", 15), ("0x10", 16), ("-3", -3), ("1e-30", 1e-30), ("2.5E+3", 2500.0),
    ("3.", 3.0), (".5", 0.5), ("-.inf", -math.inf)])
def test_numbers_of_the_core_schema_are_numbers(text, value):
    assert _value(text) == value and type(_value(text)) is type(value)


@pytest.mark.parametrize("text", ["1:30", "0b101", "1_000", "+0x10", "2024-01-02", "1.5:30"])
def test_yaml_11_only_forms_are_text(text):
    assert _value(text) == text


def test_a_tagged_mapping_carries_its_tag_and_private_top_level_keys_are_dropped():
    data = construct(compose("_base: &b {x: 1}\ndriver: !Serial {<<: *b, port: p}"))
    assert data == {"driver": {"x": 1, "port": "p", "_tag": "!Serial"}}


def test_empty_text_is_none():
    assert construct(compose("")) is None


@pytest.mark.parametrize("text", ["1:30", "0b101", "1_000", "+0x10", "-0x1F", "1_000.5", "1._"])
def test_a_yaml_11_number_the_core_schema_reads_as_text_is_told(text):
    from tegrasp_drake.rig.core_schema_yaml import yaml11_only_number
    assert yaml11_only_number(text) and _value(text) == text


@pytest.mark.parametrize("text", [
    "12", "017", "1e-9", "0x10",  # numbers in both versions, or only in the core schema
    "0o8", "0_9", "+0o17", "0:30", "1.5:30", "2024-01-02", "abc"])  # text in YAML 1.1 too
def test_a_number_of_the_core_schema_or_text_of_yaml_11_is_not_told(text):
    from tegrasp_drake.rig.core_schema_yaml import yaml11_only_number
    assert not yaml11_only_number(text)
