"""YAML text to data with scalars resolved as YAML 1.2's core schema resolves them (YAML 1.2.2,
section 10.3.2, https://yaml.org/spec/1.2.2/#1032-tag-resolution), the one loader of every
configuration the package reads (typed_yaml.parse_yaml).

PyYAML resolves plain scalars by YAML 1.1, where `1:30` is the integer 90 (base 60), `0b101` is 5,
`017` is 15 (octal), `1_000` is 1000, `2024-01-02` a date, `1e-9` text and `yes`/`no`/`on`/`off`
booleans. The core schema reads decimal, `0o` octal and `0x` hexadecimal integers (`017` is 17),
floats with or without a dot or an exponent (`1e-9`), and `true`/`false` (three cases each) as
booleans; every other plain scalar is text (`yes`, `off`), which a numeric or true/false field
then refuses by its type. Null keeps PyYAML's forms, the core schema's (`~`, `null`, empty).
The data is then dumped for Drake's `yaml_load_typed`, which quotes a text `yes`. As Drake's
`yaml_load` does, a tag `!Name` on a mapping adds `_tag: "!Name"` to it (a variant's type; a
field that is no variant refuses it, typed_yaml.check_fields), and top-level keys starting with `_` (templates for aliases) are dropped."""

import math
import re

import yaml

from tegrasp_drake.rig.integer_text import CORE_INT, read_integer

INT_TAG = "tag:yaml.org,2002:int"
FLOAT_TAG = "tag:yaml.org,2002:float"
BOOL_TAG = "tag:yaml.org,2002:bool"
_DROPPED_TAGS = (INT_TAG, FLOAT_TAG, BOOL_TAG, "tag:yaml.org,2002:timestamp")

CORE_BOOL = re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$")

CORE_FLOAT = re.compile(r"""^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?
    |[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$""", re.X)


class CoreSchemaLoader(yaml.SafeLoader):
    """PyYAML's safe loader with the core schema's numbers and booleans (module docstring)."""

    yaml_implicit_resolvers = {
        first: [(tag, regexp) for tag, regexp in resolvers if tag not in _DROPPED_TAGS]
        for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()}

    def construct_core_int(self, node) -> int:
        return read_integer(self.construct_scalar(node))

    def construct_core_float(self, node) -> float:
        text = self.construct_scalar(node)
        if not CORE_FLOAT.match(text):
            raise yaml.constructor.ConstructorError(
                None, None, f"!!float {text!r} is not a YAML 1.2 number", node.start_mark)
        lowered = text.lower()
        if lowered.endswith((".inf", ".nan")):
            return -math.inf if lowered.startswith("-") else (
                math.nan if lowered.endswith("nan") else math.inf)
        return float(text)

    def construct_variant(self, name: str, node) -> dict:
        tag = "!" + name
        if not isinstance(node, yaml.MappingNode):
            raise yaml.constructor.ConstructorError(
                None, None, f"the tag {tag} must mark a mapping", node.start_mark)
        return {**self.construct_mapping(node, deep=True), "_tag": tag}


# The integer resolver first: "12" matches both expressions and is an integer.
CoreSchemaLoader.add_implicit_resolver(INT_TAG, CORE_INT, list("-+0123456789"))
CoreSchemaLoader.add_implicit_resolver(FLOAT_TAG, CORE_FLOAT, list("-+.0123456789"))
CoreSchemaLoader.add_implicit_resolver(BOOL_TAG, CORE_BOOL, list("tTfF"))
CoreSchemaLoader.add_constructor(INT_TAG, CoreSchemaLoader.construct_core_int)
CoreSchemaLoader.add_constructor(FLOAT_TAG, CoreSchemaLoader.construct_core_float)
CoreSchemaLoader.add_multi_constructor("!", CoreSchemaLoader.construct_variant)


def yaml11_only_number(text: str) -> bool:
    """Whether plain `text` is a number by YAML 1.1 (PyYAML's own implicit resolvers,
    yaml.SafeLoader) and text by the core schema (CoreSchemaLoader): `1:30`, `0b101`,
    `1_000`, `+0x10`. Each version's grammar is its loader's; none is written a third time."""
    numbers = (INT_TAG, FLOAT_TAG)
    return (_implicit_tag(yaml.SafeLoader, text) in numbers
            and _implicit_tag(CoreSchemaLoader, text) not in numbers)


def yaml11_only_boolean(text: str) -> bool:
    """Whether plain `text` is a boolean by YAML 1.1 (PyYAML's resolvers) and text by the
    core schema: `yes`, `No`, `ON`, `off`."""
    return (_implicit_tag(yaml.SafeLoader, text) == BOOL_TAG
            and _implicit_tag(CoreSchemaLoader, text) != BOOL_TAG)


def _implicit_tag(loader_class, text: str) -> str:
    """The tag `loader_class` resolves a plain (unquoted) scalar `text` to."""
    loader = loader_class("")
    try:
        return loader.resolve(yaml.ScalarNode, text, (True, False))
    finally:
        loader.dispose()


def compose(text: str):
    """The node tree of one YAML document (None for an empty one), tags resolved as above."""
    loader = CoreSchemaLoader(text)
    try:
        return loader.get_single_node()
    finally:
        loader.dispose()


def construct(root):
    """The data a node tree from `compose` holds, top-level keys starting with `_` dropped."""
    if root is None:
        return None
    loader = CoreSchemaLoader("")
    try:
        data = loader.construct_document(root)
    finally:
        loader.dispose()
    if isinstance(data, dict):
        data = {key: value for key, value in data.items()
                if not (isinstance(key, str) and key.startswith("_"))}
    return data
