"""Fields whose empty value ('' or []) means "not set": the object's shape, sizes, file and
colour (the built-in object's), a controller's thresholds (the hand's). The package leaves
them empty; a user who writes one empty is refused (typed_yaml.check_fields) rather than
silently given what empty stands for: they leave the field out for that."""

import dataclasses

_KEY = "tegrasp_empty_means"


def unset_when_empty(means: str, field: dataclasses.Field | None = None) -> dataclasses.Field:
    """`field` (default: a text field, default '') marked as "not set" while empty; `means`
    says what an empty value stands for, e.g. "the built-in object's sizes"."""
    field = field if field is not None else dataclasses.field(default="")
    return dataclasses.field(default=field.default, default_factory=field.default_factory,
                             metadata={**field.metadata, _KEY: means})


def empty_meaning(field: dataclasses.Field) -> str | None:
    """What an empty value of `field` stands for, or None if empty is an ordinary value."""
    return field.metadata.get(_KEY)


def unset_paths(config) -> set[tuple[str, ...]]:
    """The field paths, e.g. ("object", "size"), of `config` (a dataclass) and the dataclasses
    it holds that are marked unset_when_empty and are empty."""
    paths = set()
    for field in dataclasses.fields(config):
        value = getattr(config, field.name)
        if dataclasses.is_dataclass(value):
            paths |= {(field.name,) + path for path in unset_paths(value)}
        elif empty_meaning(field) is not None and len(value) == 0:
            paths.add((field.name,))
    return paths


def without_unset_fields(block_yaml: str, config) -> str:
    """`block_yaml`, the block-style YAML of `config` (yaml_dump_typed's), without the lines of
    its empty "not set" fields, so that the text reads back as a user's file does."""
    unset = unset_paths(config)
    if not unset:
        return block_yaml
    kept, keys = [], []  # keys: (indent, key) of the mappings the line sits in
    for line in block_yaml.splitlines(keepends=True):
        body = line.lstrip(" ")
        indent = len(line) - len(body)
        key, colon, value = body.partition(":")
        if not colon or key.startswith(("-", "{", "[", "'", '"')):
            kept.append(line)
            continue
        keys = [(i, k) for i, k in keys if i < indent] + [(indent, key)]
        path = tuple(k for _, k in keys)
        if path in unset and value.strip() in ("''", "[]"):
            continue
        kept.append(line)
    return "".join(kept)
