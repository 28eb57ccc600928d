"""Typed configuration from YAML (scenarios, the hardware config, sweep specs) with
one-line errors that name the field. `parse_yaml`, the one way YAML text becomes data (files
and `--set` alike), reads scalars as YAML 1.2's core schema does (core_schema_yaml.py) after
refusing duplicate keys, oversized text, alias bombs and integers past the bounded reader's
range (integer_text.py);
`check_fields` names the first unknown, missing, mistyped, non-finite or null field by its
dotted path (a section written as null: refuse_null_section, which every loader uses);
`load_typed` then builds the dataclass with `yaml_load_typed`."""

import argparse
import collections.abc
import copy
import dataclasses
import functools
import math
import os
import pathlib
import re
import stat
import sys
import types
import typing

import yaml

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.rig.core_schema_yaml import (CORE_FLOAT, FLOAT_TAG, INT_TAG, compose,
                                                construct, yaml11_only_boolean,
                                                yaml11_only_number)
from tegrasp_drake.rig.echo import ECHO_CHARS, shorten, shown, undecoded_byte
from tegrasp_drake.rig.integer_text import IntegerTextError, read_integer
from tegrasp_drake.rig.number_text import float_beyond_problem, number_text
from tegrasp_drake.rig.ranges import holds_settings, number_problem, python_scalar, range_of
from tegrasp_drake.rig.unset_fields import empty_meaning
from tegrasp_drake.rig.files import (InputTooLargeError, NotAFileError, error_line, read_bounded,
                                     read_error_remedy)


class ConfigError(ValueError):
    """A configuration file, field or value is wrong; the message names it, on one line (a
    line break inside a value it quotes is shown as \\n). `where`: the place in the text
    ("line N, column M"), when parse_yaml found it, for a caller that words the error itself
    (one that must not quote a file's content still says where)."""

    def __init__(self, message: str = "", *, where: str | None = None):
        super().__init__(error_line(str(message)))
        self.where = where


class YamlSyntaxError(ConfigError):
    """Text that is not YAML (parse_yaml), told apart from YAML past the reader's limits by a
    caller that also takes free text."""


class ForeignTagError(ConfigError):
    """A configuration file whose top-level tag is not its kind's (parse_yaml_file); `tag`
    is that tag, for a loader that names a likely mix-up in its own words."""

    def __init__(self, message: str, *, tag: str):
        super().__init__(message)
        self.tag = tag


class UnreadableFileError(ConfigError):
    """A configuration file that cannot be read (missing, a folder or device, no permission,
    an I/O error): bad input, exit 1 wherever it is given (docs/user-guide.md, "Exit codes"),
    not a file refused for what it holds (a sweep, transfer or sensitivity spec: exit 2)."""


def read_yaml_file(path: str | pathlib.Path, what: str, *, kind: type | None):
    """The parsed content of the YAML file at `path` (None if it is empty); `what` names the
    file in errors, e.g. "the scenario file"; `kind`: the class whose tag the file's top level
    may carry (parse_yaml_file)."""
    text = read_yaml_text(path, what)
    return parse_yaml_file(text, path, what, kind=kind)


def parse_yaml_file(text: str, path: str | pathlib.Path, what: str, *, kind: type | None):
    """parse_yaml's data of a configuration file's `text` (None if it is empty), the one way
    every file kind is parsed: ForeignTagError when its top-level mapping carries a tag other
    than `kind`'s own (`!SweepSpec` for kind=SweepSpec; no tag at all for kind=None, a file
    that is no one class's, e.g. the scenario file's mapping of names), which parse_yaml
    would drop: a file of another kind, or a misspelt tag, is not read without a word."""
    if not text:
        return None
    data = parse_yaml(text, str(path))
    tag = top_level_tag(text)
    if tag is not None and (kind is None or tag != f"!{kind.__name__}"):
        remedy = (f"tag it !{kind.__name__} or remove the tag" if kind is not None else
                  "remove the tag (its top level takes none)")
        read_as = f"a {kind.__name__}" if kind is not None else what
        raise ForeignTagError(f"{path}: the file is tagged {shorten(tag)}, but it is read as "
                              f"{read_as}; {remedy}", tag=tag)
    return data


def read_yaml_text(path: str | pathlib.Path, what: str) -> str:
    """The text of the YAML file at `path`, unparsed; UnreadableFileError when there is no
    file to read (missing, a folder or device, no permission, an I/O error), ConfigError for
    text that is no configuration's (too large, not UTF-8), never its content."""
    path = pathlib.Path(path)
    try:
        if path.is_dir():
            raise UnreadableFileError(f"{path}: cannot read {what}: it is a folder; give a file")
        text = read_bounded(path, MAX_YAML_BYTES).decode("utf-8")
    except FileNotFoundError:
        raise UnreadableFileError(f"{path}: cannot read {what}: it does not exist") from None
    except NotAFileError as e:
        raise UnreadableFileError(f"{path}: cannot read {what}: it {e.strerror}") from None
    except InputTooLargeError:
        raise ConfigError(f"{path}: more than {MAX_YAML_BYTES} bytes of YAML; a configuration "
                          f"is at most {MAX_YAML_BYTES} bytes") from None
    except UnicodeDecodeError as e:
        raise ConfigError(f"{path}: cannot read {what}: it is not UTF-8 text (byte "
                          f"{e.start}); give a YAML file") from None
    except OSError as e:
        raise UnreadableFileError(f"{path}: cannot read {what}: {os_error_text(e)}; "
                                  f"{read_error_remedy(e)}") from None
    return text


# read_yaml_file_cached's parsed files: (path, device, inode, size, mtime in ns, kind) -> data.
_PARSED_FILES: dict = {}
_MAX_PARSED_FILES = 16  # a few scenario files; the oldest is dropped past it


def read_yaml_file_cached(path: str | pathlib.Path, what: str, *, kind: type | None):
    """read_yaml_file's data, parsed once per process for each version of a regular file
    (its path, device, inode, size and modification time: an edited or replaced file is read
    again); a deep copy each call, so a caller may change it (LoadScenario applies --set
    assignments to its entry). For a file many loads read in one run: the scenario file,
    read once a world and controller when a study's worlds are checked."""
    try:
        status = os.stat(path)
    except OSError:
        status = None
    if status is None or not stat.S_ISREG(status.st_mode):
        return read_yaml_file(path, what, kind=kind)  # its error names the problem
    key = (os.path.abspath(path), status.st_dev, status.st_ino, status.st_size,
           status.st_mtime_ns, kind)
    if key not in _PARSED_FILES:
        data = read_yaml_file(path, what, kind=kind)
        if len(_PARSED_FILES) >= _MAX_PARSED_FILES:
            del _PARSED_FILES[next(iter(_PARSED_FILES))]
        _PARSED_FILES[key] = data
    return copy.deepcopy(_PARSED_FILES[key])


def top_level_tag(text: str) -> str | None:
    """The YAML tag (`!SimulatedStationConfig`) of `text`'s top-level mapping, which parse_yaml
    drops, or None; `text` is YAML parse_yaml has read."""
    root = compose(text)
    tag = getattr(root, "tag", "")
    return tag if isinstance(root, yaml.MappingNode) and tag.startswith("!") else None


def require_fields(data, path, what: str, advice: str) -> None:
    """ConfigError unless a configuration file's parsed YAML holds a field: an empty or
    comment-only file, `{}` or a lone tag (`!Scenario {}`) is a mistake, not a request for
    every default. `what` names the file ("the sweep spec"), `advice` says what to write."""
    if data is None or (isinstance(data, dict) and not set(data) - {"_tag"}):
        raise ConfigError(f"{path}: {what} is empty (no fields); {advice}")


def require_mapping(data, path, what: str, contents: str, *, echo: bool = True) -> None:
    """ConfigError unless a configuration file's top level is a mapping: a file whose top
    level is a list or a scalar says so, in the words of `what` ("the scenario file", kind=None) and
    `contents` (what its keys are: "scenario names"), not as a missing key. echo=False: a
    file a field names, which may be any file the user can read: the error says the kind and
    size of what it found, never its content (content_words)."""
    if not isinstance(data, dict):
        found = _describe(data) if echo else content_words(data)
        raise ConfigError(f"{path}: {what}'s top level must be a mapping of {contents}, got "
                          f"{found}")


def content_words(data) -> str:
    """What parsed YAML data is, without its content: "a list of 3 items", "text of 1222
    characters" (an error about a file a field names, which may be any readable file)."""
    if isinstance(data, (list, dict)):
        count = len(data)
        kind = "list" if isinstance(data, list) else "mapping"
        return f"a {kind} of {count} {'item' if count == 1 else 'items'}"
    if isinstance(data, str):
        return f"text of {len(data)} characters"
    return f"a {type(data).__name__}"


def require_known_keys(data: dict, schema, path, what: str, advice: str) -> None:
    """ConfigError unless every top-level key of a file a field names is a field of `schema`:
    else it is not such a file, said by how many keys are not, never which (the file may be
    any readable one; its first line would be shown)."""
    fields = {field.name for field in dataclasses.fields(schema)}
    unknown = [key for key in data if key != "_tag" and key not in fields]
    if unknown:
        raise ConfigError(f"{path}: is not {what} ({len(unknown)} of its {len(data)} top-level "
                          f"keys are not one of {', '.join(sorted(fields))}): {advice}")


def refuse_null_section(value, source: str, path: str, *, required: bool = False) -> None:
    """ConfigError naming `source` and the field `path` when a section (a field whose value
    is a mapping of fields: `gripper:`, `object: null`) is written as null: neither its
    defaults nor an error about a mapping's type, but what to do. `required`: a section
    with no default (a transfer spec's worlds), which cannot be removed."""
    if value is None:
        advice = ("give its fields" if required else
                  "give its fields, or remove the section to use the defaults")
        raise ConfigError(f"{source}: field '{path}' is empty (null): {advice}")


def optional_section(data: dict, name: str, source: str, absent):
    """data[name], a section, or `absent` when it is left out; a null the user wrote is
    refused (refuse_null_section)."""
    if name not in data:
        return absent
    refuse_null_section(data[name], source, name)
    return data[name]


def optional_field(data: dict, name: str, source: str, absent):
    """data[name], or `absent` when the field is left out; ConfigError for a null the user
    wrote, as check_fields refuses one (a null read as "left out" would put a default, e.g.
    the paper's whole sweep, in place of what the user gave)."""
    if name not in data:
        return absent
    if data[name] is None:
        raise ConfigError(f"{source}: field '{name}' is null: give a value, or leave the "
                          "field out to take its default")
    return data[name]


# A configuration is a few kB; these bound what a mistaken or hostile file can cost.
MAX_YAML_BYTES = 1_000_000
MAX_YAML_NODES = 100_000
# The longest key YAML reads without `? ` before it (an implicit key: YAML 1.2.2, section
# 7.4.2, "limited to 1024 Unicode characters"); past it PyYAML's scanner no longer takes the
# text for a key and stops at its ':' with "mapping values are not allowed here".
MAX_YAML_KEY_CHARS = 1024


def parse_yaml(text: str, source: str, *, line_offset: int = 0, column_offset: int = 0,
               root_key: str | None = None):
    """The data of YAML `text` (module docstring); ConfigError "SOURCE: ..." in one line
    naming the line and column (less the offsets of text the caller put before it), or the
    field by its dotted path (`root_key`: the name to give the top-level key, for a --set
    value the caller wrapped in one); YamlSyntaxError for text that is not YAML. None for
    empty text."""
    if not text:
        return None
    if "\x00" in text:
        raise ConfigError(f"{source}: holds a NUL byte; it is not YAML text")
    if len(text.encode("utf-8", errors="replace")) > MAX_YAML_BYTES:
        raise ConfigError(f"{source}: {len(text.encode('utf-8', errors='replace'))} bytes of "
                          f"YAML; a configuration is at most {MAX_YAML_BYTES} bytes")
    try:
        root = compose(text)
        if root is not None:
            _check_nodes(root, source, line_offset, column_offset, root_key)
        return construct(root)
    except yaml.YAMLError as e:
        problem = (_over_long_key(text, e, line_offset)
                   or _yaml_problem(e, line_offset, column_offset))
        raise YamlSyntaxError(f"{source}: not valid YAML: {problem}",
                              where=_error_place(e, line_offset, column_offset)) from None
    except RecursionError:
        raise ConfigError(f"{source}: the YAML nests deeper than Python's recursion limit "
                          f"({sys.getrecursionlimit()} levels); no configuration nests more "
                          "than a few levels: give a flat mapping of its fields") from None


def _number_node_problem(node) -> str | None:
    """Why the number a plain YAML scalar `node` writes cannot be read as one, in words that
    follow its field: an integer beyond the bounded reader's range, a float no float holds
    (`.inf` and `.nan` are read, then refused as not finite by the field's check); else None."""
    if node.tag == INT_TAG:
        try:
            read_integer(node.value)
        except IntegerTextError as e:
            return str(e)
    elif node.tag == FLOAT_TAG and CORE_FLOAT.match(node.value) and not node.value.lower(
            ).endswith((".inf", ".nan")):
        return float_beyond_problem(node.value)
    return None


def _check_nodes(root, source: str, line_offset: int, column_offset: int,
                 root_key: str | None = None) -> None:
    """Refuses duplicate mapping keys, an alias expansion past MAX_YAML_NODES, an integer
    the bounded reader refuses (integer_text.py: Python would not convert it) and a float no
    float holds (number_text.float_beyond_problem: `1e-400` would be read as 0)."""
    sizes = {}  # id(node) -> its size with every alias expanded; len(sizes): values written

    def where(node) -> str:
        mark = node.start_mark
        column = mark.column + 1 - (column_offset if mark.line == 0 else 0)
        return f"line {mark.line + 1 - line_offset}, column {column}"

    def size(node, path: str) -> int:
        if id(node) in sizes:
            return sizes[id(node)]
        sizes[id(node)] = 1  # a node that holds itself counts once
        if node.tag.startswith("tag:yaml.org,2002:python/"):
            raise ConfigError(f"{source}: {where(node)}: a Python object tag "
                              f"(!!{node.tag.split(':', 2)[2]}) is never loaded; give a "
                              "plain value", where=where(node))
        if isinstance(node, yaml.ScalarNode):
            problem = _number_node_problem(node)
            if problem is not None:
                field = f"field '{path}' " if path else ""
                raise ConfigError(f"{source}: {field}({where(node)}) {problem}; write a number "
                                  "in the field's range", where=where(node))
        total = 1
        if isinstance(node, yaml.MappingNode):
            seen = {}
            for key, value in node.value:
                if key.tag not in ("tag:yaml.org,2002:str", "tag:yaml.org,2002:merge"):
                    what = (f"{key.tag.rsplit(':', 1)[-1]} {key.value!r}; quote it"
                            if isinstance(key, yaml.ScalarNode) else
                            "a list" if isinstance(key, yaml.SequenceNode) else "a mapping")
                    raise ConfigError(f"{source}: {where(key)}: a key must be a name (text), "
                                      f"got {what}"[:300], where=where(key))
                if isinstance(key, yaml.ScalarNode):  # a merge key '<<' too
                    if key.value in seen:
                        merging = key.tag == "tag:yaml.org,2002:merge"
                        raise ConfigError(
                            f"{source}: key '{key.value}' appears twice ({seen[key.value]} "
                            f"and {where(key)}); keep one"
                            + ("; to merge several mappings give one '<<' a list of them"
                               if merging else ""), where=where(key))
                    seen[key.value] = where(key)
                name = str(key.value) if isinstance(key, yaml.ScalarNode) else "<<"
                if not path and root_key is not None:
                    name = root_key
                total += size(key, path) + size(value, f"{path}.{name}" if path else name)
        elif isinstance(node, yaml.SequenceNode):
            total += sum(size(item, f"{path}[{k}]") for k, item in enumerate(node.value))
        if total > MAX_YAML_NODES and len(sizes) > MAX_YAML_NODES:  # written, not aliased
            raise ConfigError(f"{source}: holds more than {MAX_YAML_NODES} values (keys, "
                              f"values and entries; {where(node)}); a configuration is "
                              "smaller: split the file, or keep only the entries you use",
                              where=where(node))
        if total > MAX_YAML_NODES:
            raise ConfigError(f"{source}: the YAML's aliases expand to more than "
                              f"{MAX_YAML_NODES} values ({where(node)}); write the values "
                              "out, or use fewer nested aliases", where=where(node))
        sizes[id(node)] = total
        return total

    size(root, "")


def _over_long_key(text: str, error: yaml.YAMLError, line_offset: int = 0) -> str | None:
    """For a YAML error at the ':' after a key longer than MAX_YAML_KEY_CHARS, that key's
    line and length in words; None for any other error."""
    mark = getattr(error, "problem_mark", None)
    if mark is None:
        return None
    lines = text.splitlines()
    line = lines[mark.line] if mark.line < len(lines) else ""
    if line[mark.column:mark.column + 1] != ":":
        return None
    # the key: the text before the ':' after the indentation, a '- ' or '? ', or a flow
    # collection's last '{', '[' or ','
    before = re.sub(r"^\s*(?:[-?]\s+)*", "", line[:mark.column])
    key = re.split(r"[{\[,]", before)[-1].strip()
    if len(key) <= MAX_YAML_KEY_CHARS:
        return None
    return (f"line {mark.line + 1 - line_offset}: a key of {len(key)} characters; keys are at "
            f"most {MAX_YAML_KEY_CHARS} characters")


def _error_place(error: yaml.YAMLError, line_offset: int = 0,
                 column_offset: int = 0) -> str | None:
    """Where a YAML error is, "line N, column M" in the text given; None if PyYAML did not
    say."""
    mark = getattr(error, "problem_mark", None)
    if mark is None:
        return None
    column = mark.column + 1 - (column_offset if mark.line == line_offset else 0)
    return f"line {mark.line + 1 - line_offset}, column {max(column, 1)}"


def _yaml_problem(error: yaml.YAMLError, line_offset: int = 0, column_offset: int = 0) -> str:
    """A YAML error in one line: what and where (line, column in the text given)."""
    place = _error_place(error, line_offset, column_offset)
    problem = getattr(error, "problem", None) or str(error).splitlines()[0]
    where = f"{place}: " if place else ""
    context = getattr(error, "context", None)
    if "character '\\t'" in problem:  # PyYAML's words for a tab where a token starts
        return f"{where}a tab where YAML takes only spaces (it never indents with tabs); use spaces"
    return (where + problem + (f" ({context})" if context else "")).replace("\n", " ")


class RefinedSettings(tuple):
    """KEY=VALUE settings the package composed, a later one refining an earlier one (a
    transfer world's preset, then its overrides, then the sweep's; a sweep trial's, checked
    with its sweep): not one list the user wrote, so key_set_twice lets a key be set twice."""
    __slots__ = ()


class SetTwice(typing.NamedTuple):
    """Where a list of settings sets one key twice (key_set_twice): setting `then` sets
    `key`, which setting `first` set to another value; `dropped`: `then` is a mapping that
    replaces the section holding `key` and leaves it out, so the earlier value would be lost
    without a word."""
    first: int
    then: int
    key: str
    dropped: bool = False


def _leaves(key: str, value, leaves: dict) -> None:
    """Each dotted key a setting of `key` to `value` sets, with its value: a mapping's
    entries (nested ones by their full dotted key), anything else the key itself."""
    if isinstance(value, dict) and value:
        for name, item in value.items():
            _leaves(f"{key}.{name}", item, leaves)
    else:
        leaves[key] = value


def _setting_leaves(setting: str) -> tuple[dict, str | None] | None:
    """({dotted key: value} a KEY=VALUE setting sets, the section it replaces when its value
    is a mapping), or None for a text that is no setting, or whose value is no YAML (its own
    check names it)."""
    if not isinstance(setting, str) or assignment_problem(setting):
        return None
    key, text = assignment_key(setting), setting.split("=", 1)[1]
    try:
        value = parse_yaml("value: " + text, "setting")["value"] if text.strip() else ""
    except (ConfigError, TypeError):
        return None
    leaves: dict = {}
    _leaves(key, value, leaves)
    return leaves, key if isinstance(value, dict) else None


def key_set_twice(settings) -> SetTwice | None:
    """The first place a list of KEY=VALUE settings the user wrote (--set given twice, a
    spec's scenario_overrides, LoadScenario's overrides) sets one key twice to two values,
    or None: neither may silently win, as a YAML file may not repeat a key. A mapping value
    sets each key it holds (`object={mass: 0.1}` sets object.mass, as `object.mass=0.1`
    does), nested ones too, and replaces its section: a key an earlier setting set inside it
    and the mapping leaves out is dropped (SetTwice.dropped). A key and a section holding it
    set by two settings are one key set twice. The same value twice is no conflict. A text
    that is no setting is skipped (its own check names it); RefinedSettings are not
    checked."""
    if isinstance(settings, RefinedSettings):
        return None
    earlier: dict = {}  # dotted key -> (index of the first setting that set it, value)
    for k, setting in enumerate(settings):
        parsed = _setting_leaves(setting)
        if parsed is None:
            continue
        leaves, section = parsed
        for key, value in leaves.items():
            for other, (i, before) in earlier.items():
                if other == key and before != value:
                    return SetTwice(i, k, key)
                if keys_overlap(other, key) and other != key and other not in leaves:
                    refines = key.startswith(other + ".") and before == {}  # `x={}`, `x.y=1`
                    replaced = section is not None and other.startswith(section + ".")
                    if not refines and not replaced:  # replaced: told as dropped, below
                        return SetTwice(i, k, min(other, key, key=len))
        if section is not None:
            for other, (i, _) in earlier.items():
                if other.startswith(section + ".") and other not in leaves:
                    return SetTwice(i, k, other, dropped=True)
        for key, value in leaves.items():
            earlier.setdefault(key, (k, value))
    return None


def set_twice_words(settings, twice: SetTwice, place=None) -> str:
    """key_set_twice's finding in words that follow what sets them ("--set ", "field
    'x' "): "sets KEY twice ('A', then 'B'); set it once", each setting with its index when
    `place` is true (a list in a file or an argument)."""
    def at(k):
        return f"{shown(settings[k])}{f' at [{k}]' if place else ''}"
    if twice.dropped:
        section = assignment_key(settings[twice.then])
        return (f"sets {twice.key} twice ({at(twice.first)}, then {at(twice.then)}, which "
                f"replaces the whole section {section} without it); set it once: in that "
                "mapping, or after it")
    return f"sets {twice.key} twice ({at(twice.first)}, then {at(twice.then)}); set it once"


def refuse_a_key_set_twice(settings, source: str, path: str, kind: str = "field") -> None:
    """ConfigError naming `source` and the field (or argument: `kind`) `path` when
    `settings`, a list of KEY=VALUE settings a file or a caller gives, sets one key twice to
    two values (key_set_twice)."""
    twice = key_set_twice(settings)
    if twice:
        raise ConfigError(f"{source}: {kind} '{path}' {set_twice_words(settings, twice, True)}")


def set_words(assignment: str, option: str = "--set") -> str:
    """How an error names a --set assignment (or one of another `option`, such as
    --config-set): `--set 'KEY=VALUE'`, the value cut to about ECHO_CHARS."""
    key, equals, text = assignment.partition("=")
    return f"{option} '{shorten(key)}{equals}{shorten(text)}'"


def _echo(assignment: str, limit: int = ECHO_CHARS) -> str:
    """An assignment as an error's source names it (`KEY=VALUE`), its parts cut (shorten)
    to about `limit` characters each."""
    key, equals, value = assignment.partition("=")
    return shorten(key, limit) + equals + shorten(value, limit)


# A source longer than this names only the assignments at fault (loaded_with_overrides).
MAX_SOURCE_CHARACTERS = 200
# How much of each assignment a long source keeps when the message names none of them.
UNNAMED_ASSIGNMENT_CHARS = 40


def loaded_with_overrides(load, file_source: str, overrides: typing.Sequence[str],
                          option: str = "--set"):
    """load(source) for a configuration read from a file and changed by the command line's
    `option` assignments (--set, --config-set): a ConfigError it raises names them as its
    source (`FILE --set 'KEY=VALUE'`), so that a bad value given on the command line is not
    blamed on the file. When the whole list is long (over MAX_SOURCE_CHARACTERS: a preset's
    or a sweep's many assignments would bury the one at fault) only the assignments whose
    setting the message names are kept, with how many others there were; a short list stays
    whole: a rule across settings may be broken by one it does not name. When the message
    names none of them (a rule across settings, named by another field), every assignment
    is kept, each cut to about UNNAMED_ASSIGNMENT_CHARS with its start kept, so that the one
    at fault can still be seen."""
    source = file_source + "".join(f" {option} {_echo(a)}" for a in overrides)
    try:
        return load(source)
    except ConfigError as error:
        message = str(error)
        if not message.startswith(source) or len(source) <= MAX_SOURCE_CHARACTERS:
            raise
        rest = message[len(source):]
        named = [a for a in overrides if f"'{assignment_key(a)}" in rest]
        if not named:
            raise ConfigError(file_source + "".join(
                f" {option} {_echo(a, UNNAMED_ASSIGNMENT_CHARS)}" for a in overrides)
                + rest) from None
        others = len(overrides) - len(named)
        raise ConfigError(file_source + "".join(f" {option} {_echo(a)}" for a in named)
                          + (f" (and {others} other {option})" if others else "")
                          + rest) from None


def assignment_problem(assignment: str, example: str = "object.mass") -> str | None:
    """Why `assignment` is no `KEY=VALUE` with KEY a dotted field name (such as `example`),
    each of its names given (not '', '.a', 'a..b' or 'a.'), in words that follow
    "--set 'ASSIGNMENT': "; None if it is one. A byte that is not UTF-8 (an argument's
    surrogate, `$'\\xff'` in a shell) is refused first, by its byte, key or value alike."""
    key, equals, _ = assignment.partition("=")
    undecoded = undecoded_byte(assignment)
    if undecoded:
        position, byte = undecoded
        part = "key" if not equals or position < len(key) else "value"
        return (f"byte 0x{byte:02x} (character {position + 1}, in the {part}) is not UTF-8; "
                f"give the {part} in UTF-8 text")
    if not equals or any(not name.strip() for name in key.split(".")):
        return f"expected KEY=VALUE with KEY a dotted field name such as {example}"
    return None


def set_option(text: str, example: str = "object.mass") -> str:
    """argparse's type of --set (a scenario field, such as `example`): the assignment as
    given, or a usage error (exit 2) naming it (assignment_problem); '' is left to the
    command line's refusal of empty values."""
    problem = assignment_problem(text, example) if text else None
    if problem:
        # argparse puts "argument --set: " before it
        raise argparse.ArgumentTypeError(f"{set_words(text).removeprefix('--set ')}: {problem}")
    return text


def config_set_option(text: str) -> str:
    """argparse's type of --config-set (a hardware config field): as set_option's."""
    return set_option(text, example="tactile.port")


def assignment_key(assignment: str) -> str:
    """The dotted KEY of a `KEY=VALUE` assignment, as apply_override reads it."""
    return assignment.split("=", 1)[0].strip()


def keys_overlap(a: str, b: str) -> bool:
    """Whether dotted keys `a` and `b` name one field, or one names a section holding the
    other: an assignment to either changes what the other sets (`gripper={pad_friction: 1}`
    sets gripper.pad_friction)."""
    return a == b or a.startswith(b + ".") or b.startswith(a + ".")


def unknown_field_problem(assignment: str, schema) -> str | None:
    """Why `assignment` (`key=value`) sets no field of the dataclass `schema`, in words, or
    None: a part of its dotted key that is no field of the section it names, or (a value that
    is a YAML mapping for a section) a key of the mapping that is none; each with the
    section's nearest field names and all of them. A section that is no dataclass (a Drake
    config class, a tagged union) is its loader's to check: None."""
    key = assignment_key(assignment)
    section, where = schema, []
    for part in key.split("."):
        if not dataclasses.is_dataclass(section):
            return None
        names = [field.name for field in dataclasses.fields(section)]
        if part not in names:
            return _not_a_field_words(".".join([*where, part]), where, part, names)
        section = typing.get_type_hints(section)[part]
        where.append(part)
    if not dataclasses.is_dataclass(section) or "=" not in assignment:
        return None
    try:
        value = yaml.safe_load(assignment.split("=", 1)[1])
    except yaml.YAMLError:
        return None  # apply_override's to tell
    names = [field.name for field in dataclasses.fields(section)]
    for sub in value if isinstance(value, dict) else ():
        if str(sub) not in names:
            return _not_a_field_words(f"{key}.{sub}", where, str(sub), names)
    return None


def _not_a_field_words(key: str, where: list, part: str, names: list) -> str:
    import difflib
    section = f"the {'.'.join(where)} section" if where else "the top level"
    close = difflib.get_close_matches(part, names, n=3, cutoff=0.5)
    nearest = f"nearest: {', '.join(close)}; " if close else ""
    return (f"'{shorten(key)}' is not a field of {section} ({nearest}its fields: "
            f"{', '.join(sorted(names))})")


def apply_override(data: dict, assignment: str, option: str = "--set",
                   example: str = "object.name") -> None:
    """Sets `key.sub=value` (YAML value) in nested YAML data; errors name the assignment as
    given with `option` (--set, --config-set); a value that is not YAML is told to quote
    text, shown on `example`, a text field of its config."""
    words = set_words(assignment, option)
    problem = assignment_problem(assignment)
    if problem:
        raise ConfigError(f"{words}: {problem}")
    key, text = assignment.split("=", 1)
    if not isinstance(data, dict):
        raise ConfigError(f"{words}: the document it would change is "
                          f"{_describe(data)}, not a mapping of fields; fix the file")
    if "\n" in text:
        raise ConfigError(f"{words}: the value must be on one line")
    prefix = "value: "
    try:
        value = (parse_yaml(prefix + text, words, column_offset=len(prefix),
                            root_key=key.strip())["value"] if text.strip() else "")
    except ConfigError as e:
        if "not valid YAML" not in str(e):
            raise
        raise ConfigError(f"{e}; the value is YAML: quote text that holds ': ', '#', '*', "
                          f"'&', '!' or brackets, e.g. {example}='a: b'") from None
    node = data
    parts = key.strip().split(".")
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise ConfigError(f"{words}: '{shorten(part)}' is not a mapping")
    node[parts[-1]] = value


def load_typed(data: dict, schema, source: str, *, stored: bool = False):
    """An instance of the dataclass `schema` from YAML data (defaults for what is not
    set), after `check_fields` (`stored`: as check_fields's)."""
    check_fields(data, schema, source, stored=stored)
    from pydrake.common.yaml import yaml_dump, yaml_load_typed  # pydrake: loaded when building
    try:
        return yaml_load_typed(schema=schema, data=yaml_dump(data), defaults=schema())
    except (RuntimeError, ValueError, yaml.YAMLError) as e:
        raise ConfigError(f"{source}: {e}") from None


def check_fields(data, schema, source: str, where: str = "", *, stored: bool = False) -> None:
    """Walks YAML data against a dataclass schema; ConfigError names the first unknown,
    missing or mistyped field (dataclasses, scalars, lists, tuples, mappings, optionals,
    tagged Unions; Drake's config classes are checked by Drake). `stored`: the text this
    package wrote (a log's or an event's scenario), whose empty "not set" fields are read as
    not set: versions before scenario_to_yaml dropped them wrote them; a user's are refused."""
    _refuse_tag(data, where, source)
    if where:  # a section; an empty file's None is require_fields's
        refuse_null_section(data, source, where, required=_has_required_fields(schema))
    if not dataclasses.is_dataclass(schema):
        # A Drake config class: let Drake check it, but name the section.
        if not isinstance(data, dict):
            raise ConfigError(f"{source}: {_field(where)}must be a mapping of "
                              f"{schema.__name__} fields ({_drake_field_names(schema)}), "
                              f"got {_describe(data)}")
        known = [field.name for field in getattr(schema, "__fields__", ())]
        for key in data if known else ():
            if key not in known and key != "_tag":  # a tag: refused above
                path = f"{where}.{key}" if where else str(key)
                raise ConfigError(f"{source}: field '{path}': unknown field '{path}' (known: "
                                  f"{', '.join(sorted(known))})")
        _check_finite_numbers(data, source, where)
        _check_drake_scalars(data, schema, source, where)
        from pydrake.common.yaml import yaml_dump, yaml_load_typed
        try:
            yaml_load_typed(schema=schema, data=yaml_dump(data))
        except (RuntimeError, ValueError, yaml.YAMLError) as e:  # YAMLError: an odd _tag
            raise ConfigError(f"{source}: field '{where}': {e}") from None
        return
    if not isinstance(data, dict):
        raise ConfigError(f"{source}: {_field(where)}must be a mapping of fields, got "
                          f"{_describe(data)}")
    hints = typing.get_type_hints(schema)
    fields = {field.name: field for field in dataclasses.fields(schema)}
    for key, value in data.items():
        path = f"{where}.{key}" if where else str(key)
        if key not in fields:
            raise ConfigError(f"{source}: field '{path}': unknown field '{path}' (known: "
                              f"{', '.join(sorted(fields))})")
        means = empty_meaning(fields[key])
        if (means is not None and not stored and isinstance(value, (str, list))
                and len(value) == 0):
            raise ConfigError(f"{source}: field '{path}' is empty: give a value, or leave it "
                              f"out for {means}")
        _check_value(value, hints[key], path, source, stored,
                     getattr(range_of(fields[key]), "unit", ""), holds_settings(fields[key]))
    for field in dataclasses.fields(schema):
        required = (field.default is dataclasses.MISSING
                    and field.default_factory is dataclasses.MISSING)
        if required and field.name not in data:
            path = f"{where}.{field.name}" if where else field.name
            raise ConfigError(f"{source}: field '{path}' is missing")


def _has_required_fields(schema) -> bool:
    """Whether a dataclass `schema` has a field with no default (a section of it cannot be
    left out to take its defaults)."""
    return dataclasses.is_dataclass(schema) and any(
        field.default is dataclasses.MISSING and field.default_factory is dataclasses.MISSING
        for field in dataclasses.fields(schema))


class ConfigTypeError(ConfigError, TypeError):
    """A config instance's field holds a value not of its declared type (check_instance)."""


def check_instance(config, source: str, where: str = "") -> None:
    """Walks a dataclass instance (built in Python, or changed after loading) against its
    type hints, as `check_fields` walks YAML data: ConfigTypeError names the first field
    whose value is not of its type, e.g. a dict, None or text where a config dataclass
    belongs; the scalars inside by check_fields's own rules. A NumPy number put into a list
    field in place is stored as the Python number it holds, as a public dataclass stores one
    assigned (api_boundary.python_numbers), so none reaches a JSON writer. Ranges:
    ranges.check_ranges."""
    hints = _type_hints(type(config))
    for field in dataclasses.fields(config):
        path = f"{where}.{field.name}" if where else field.name
        value = getattr(config, field.name)
        if field.name in hints and not (value is None and field.default is None):
            _check_instance_value(value, hints[field.name], path, source)


@functools.cache
def _type_hints(cls) -> dict:
    try:
        return typing.get_type_hints(cls)
    except Exception:  # noqa: BLE001: an annotation typing cannot resolve is not checked
        return {field.name: field.type for field in dataclasses.fields(cls)
                if not isinstance(field.type, str)}


def _is_config_class(hint) -> bool:
    return isinstance(hint, type) and (dataclasses.is_dataclass(hint)
                                       or bool(getattr(hint, "__fields__", None)))


def _refuse_type(value, words: str, path: str, source: str):
    raise ConfigTypeError(f"{source}: {_field(path)}must be {words}, got {_describe(value)}")


def _check_instance_value(value, hint, path: str, source: str) -> None:
    origin = typing.get_origin(hint)
    if hint is typing.Any or hint is object or isinstance(hint, (str, typing.TypeVar)):
        return
    if origin is typing.Annotated:
        _check_instance_value(value, typing.get_args(hint)[0], path, source)
    elif origin in (typing.Union, types.UnionType):
        members = [m for m in typing.get_args(hint) if m is not type(None)]
        if value is None:
            if len(members) < len(typing.get_args(hint)):
                return  # an optional field's "not set"
            _refuse_type(value, _type_words(hint), path, source)
        for member in members:
            if _is_config_class(member) and isinstance(value, member):
                _check_instance_value(value, member, path, source)
                return
        if len(members) == 1 or not any(_is_config_class(m) for m in members):
            for member in members:  # e.g. float | str: the first that takes it
                try:
                    _check_instance_value(value, member, path, source)
                    return
                except ConfigError:
                    if member is members[-1]:
                        raise
        _refuse_type(value, _type_words(hint), path, source)
    elif _is_config_class(hint):
        if not isinstance(value, hint):
            _refuse_type(value, f"{_type_words(hint)} (e.g. {hint.__name__}(...)), not its "
                         "fields as a mapping or a name", path, source)
        if dataclasses.is_dataclass(value):
            check_instance(value, source, path)
    elif origin in (list, tuple, collections.abc.Sequence):
        if getattr(value, "ndim", 0) >= 1 and not isinstance(value, (list, tuple)):
            raise ConfigTypeError(f"{source}: {_field(path)}{array_for_list_words(value, path)}")
        if not isinstance(value, (list, tuple)):
            _refuse_type(value, _type_words(hint), path, source)
        arguments = [a for a in typing.get_args(hint) if a is not Ellipsis]
        for k, item in enumerate(value):
            if isinstance(value, list) and python_scalar(item) is not item:
                value[k] = item = python_scalar(item)  # put in place: kept as an assigned one
            if arguments:
                element = arguments[k] if len(arguments) > 1 and k < len(arguments) else (
                    arguments[0])
                _check_instance_value(item, element, f"{path}[{k}]", source)
    elif origin in (dict, collections.abc.Mapping):
        if not isinstance(value, collections.abc.Mapping):
            _refuse_type(value, "a mapping", path, source)
        arguments = typing.get_args(hint)
        for key, item in value.items() if len(arguments) == 2 else ():
            _check_instance_value(item, arguments[1], f"{path}.{key}", source)
    elif hint in _SCALAR_WORDS:
        value = python_scalar(value)
        if hint in (int, float) and _is_scalar(value, int):  # 10**400: no reader bounded it
            problem = number_problem(value)
            if problem is not None:
                raise ConfigError(f"{source}: {_field(path)}{problem}")
        if not _is_scalar(value, hint) and not (hint is float and isinstance(value, float)):
            _check_value(value, hint, path, source)  # the YAML path's words for a scalar
        _check_text(value, path, source)
    elif isinstance(hint, type) and origin is None and not isinstance(value, hint):
        _refuse_type(value, _type_words(hint), path, source)


def array_for_list_words(array, path: str) -> str:
    """Why a NumPy array cannot be a list field's value, and what to give, in words that
    follow "field 'x'": its truth and equality are elementwise, so a check or a comparison
    deep inside would fail with no field named (a public dataclass's constructor and every
    public function's config argument refuse it in these words)."""
    name = re.sub(r"\[\d+\]$", "", path).rsplit(".", 1)[-1]
    return (f"must be a list or tuple, got {type(array).__module__}.{type(array).__name__}; "
            f"give {name}={name}.tolist()")


def _type_words(hint) -> str:
    """The type `hint` in words (an error's "must be ...")."""
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        return " or ".join(_type_words(m) for m in typing.get_args(hint))
    if hint is type(None):
        return "None"
    if hint in _SCALAR_WORDS:
        return _SCALAR_WORDS[hint][0]
    if origin in (list, tuple, collections.abc.Sequence):
        return "a list"
    name = getattr(hint, "__name__", str(hint))
    return f"{'an' if name[:1] in 'AEIOU' else 'a'} {name}"


# What a value of each scalar type must be, in an error message: alone, and in a list.
_SCALAR_WORDS = {float: ("a finite number", "finite numbers"), int: ("an integer", "integers"),
                 str: ("a string", "names"), bool: ("true or false", "true or false values")}


# A control character (C0 but tab and line breaks, which a stored scenario's YAML text holds;
# DEL) in a text field: no name, port, URL or file name of a rig holds one, the operating
# system refuses a NUL in a path (a ValueError deep in a check), an escape would drive the
# terminal an error is shown on.
_CONTROL = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")
_CONTROL_NAMES = {0: "a NUL", 27: "an escape", 127: "a DEL"}


def text_problem(text: str) -> str | None:
    """Why `text` cannot be a config's text (a name, port, URL, path), in words that follow
    "field 'x'", or None."""
    found = _CONTROL.search(text)
    if found is None:
        return None
    code = ord(found.group())
    name = _CONTROL_NAMES.get(code, "a control character")
    return (f"holds {name} (character 0x{code:02x}) at position {found.start()}: text "
            "fields take printable characters only; remove it")


def _check_text(value, path: str, source: str) -> None:
    if isinstance(value, str):
        problem = text_problem(value)
        if problem:
            raise ConfigError(f"{source}: field '{path}' {problem}, got {shown(value)}")


def _is_scalar(value, hint) -> bool:
    if hint is bool:
        return isinstance(value, bool)
    if isinstance(value, bool):
        return False
    if hint is float:
        return isinstance(value, (int, float)) and number_problem(value) is None
    return isinstance(value, hint)


def _check_finite_numbers(data, source: str, where: str) -> None:
    """Names the first NaN or infinite number in YAML data (of a Drake config class)."""
    if isinstance(data, float) and not math.isfinite(data):
        raise ConfigError(f"{source}: field '{where}' must be a finite number, got {data!r}")
    items = data.items() if isinstance(data, dict) else (
        enumerate(data) if isinstance(data, list) else ())
    for key, value in items:
        path = f"{where}[{key}]" if isinstance(data, list) else (
            f"{where}.{key}" if where else str(key))
        _check_finite_numbers(value, source, path)


def _drake_field_names(schema) -> str:
    """The fields of a Drake config class, as a message lists them ("a, b, ...")."""
    return ", ".join(field.name for field in getattr(schema, "__fields__", ())) or "its fields"


def _check_drake_scalars(data, schema, source: str, where: str) -> None:
    """Names the first field of a Drake config class's YAML data whose default is a number,
    true/false or text and whose value is not one of that type: Drake's loader reads text
    such as '0.5' into a number, where a field of ours refuses it (a quoted number is text),
    and words a list or mapping given for a name in its own terms."""
    if not isinstance(data, dict):
        return
    defaults = schema()
    for key, value in data.items():
        default = getattr(defaults, str(key), None)
        hint = next((t for t in (bool, int, float, str) if type(default) is t), None)
        if hint is not None and not _is_scalar(value, hint):
            path = f"{where}.{key}" if where else str(key)
            raise ConfigError(f"{source}: field '{path}' must be {_SCALAR_WORDS[hint][0]}, got "
                              f"{_describe(value)}{_text_as_value_hint(value, hint)}")


def require(condition: bool, source: str, path: str, words: str, value) -> None:
    """Raises ConfigError "SOURCE: field 'PATH' WORDS, got VALUE" unless `condition`."""
    if not condition:
        raise ConfigError(f"{source}: field '{path}' {words}, got {shown(value)}")


def _refuse_tag(value, path: str, source: str) -> None:
    """ConfigError if `value` is a mapping a YAML tag marks (core_schema_yaml adds its
    `_tag`) where no tag selects a variant (a Union of config classes consumes its own)."""
    if isinstance(value, dict) and "_tag" in value:
        words = f"a YAML tag ({shorten(str(value['_tag']))}) is not allowed here; remove it"
        raise ConfigError(f"{source}: field '{path}': {words}" if path else f"{source}: {words}")


def _check_value(value, hint, path: str, source: str, stored: bool = False,
                 unit: str = "", settings: bool = False) -> None:
    """check_fields's check of one value of type `hint`; `unit`: its field's declared unit;
    `settings`: its field is a list of KEY=VALUE settings (ranges.settings), said so."""
    origin = typing.get_origin(hint)
    if origin not in (typing.Union, types.UnionType):
        _refuse_tag(value, path, source)
    if origin in (typing.Union, types.UnionType):
        members = [m for m in typing.get_args(hint) if m is not type(None)]
        if value is None and len(members) < len(typing.get_args(hint)):
            # An optional field's None means "not set" (its default, e.g. the built-in
            # object's mass); a null the user writes is refused rather than read as that.
            raise ConfigError(f"{source}: field '{path}' is null: give a value, or leave "
                              "the field out to take its default")
        if len(members) == 1:
            _check_value(value, members[0], path, source, stored, unit, settings)
        else:
            member, value = _union_member(value, members, path, source)
            _check_value(value, member, path, source, stored)
    elif origin in (list, tuple):
        element = typing.get_args(hint)[0]
        if not isinstance(value, list):
            words = _SCALAR_WORDS.get(element, (None, "entries"))[1]
            fix = ""
            if element is str and isinstance(value, str) and not assignment_problem(value):
                words = "KEY=VALUE settings"  # one setting where a list of them belongs
                fix = f" (write it as a list: [{shorten(value)}])"
            elif settings:
                words = "KEY=VALUE settings"
                fix = f" (each one as --set takes it: {_settings_example(path)})"
            raise ConfigError(f"{source}: field '{path}' must be a list of {words}, got "
                              f"{_describe(value)}{fix}")
        for k, item in enumerate(value):
            if settings and not isinstance(item, str):
                raise ConfigError(f"{source}: field '{path}[{k}]' must be a KEY=VALUE setting "
                                  f"(as --set), got {_describe(item)} (write "
                                  f"{_settings_example(path)})")
            _check_value(item, element, f"{path}[{k}]", source, stored, unit)
    elif origin in (dict, collections.abc.Mapping):
        refuse_null_section(value, source, path)
        if not isinstance(value, dict):
            raise ConfigError(f"{source}: field '{path}' must be a mapping, got "
                              f"{_describe(value)}")
        for key, item in value.items():
            _check_value(item, typing.get_args(hint)[1], f"{path}.{key}", source, stored, unit)
    elif hint in _SCALAR_WORDS:
        if not _is_scalar(value, hint):
            raise ConfigError(f"{source}: field '{path}' must be {_SCALAR_WORDS[hint][0]}, got "
                              f"{_describe(value)}{_text_as_value_hint(value, hint, unit)}")
        _check_text(value, path, source)
    else:
        check_fields(value, hint, source, path, stored=stored)


def _settings_example(path: str) -> str:
    """A list of one setting, written as the field at `path` takes it."""
    return f"{path.rsplit('.', 1)[-1]}: [grasp.grip_force=50.0]"


def _text_as_value_hint(value, hint, unit: str = "") -> str:
    """For a number or boolean read as text (quoted, or in a form only YAML 1.1 reads as a
    number or boolean: `yes`, `off`), how to write it as a value of the field's type: decimal
    digits, an integer field's without a point or exponent; true or false. A number written
    with a unit (`150 g`): the field's `unit`, and the number in it where the unit is one
    of its prefixed forms (_unit_converted)."""
    if hint is bool and isinstance(value, str):
        if yaml11_only_boolean(value.strip()):
            return " (YAML 1.2 reads yes, no, on and off as text: write true or false)"
        return " (write true or false, without quotes)"
    if hint in (float, int) and isinstance(value, str):
        if yaml11_only_number(value.strip()):
            return (" (numbers are read as YAML 1.2 reads them: base-60 1:30, binary 0b101 and "
                    "1_000 are text; write the number in decimal digits)")
        try:
            number = float(value)
        except ValueError:
            return _unit_hint(value, unit)
        if not math.isfinite(number):
            return ""
        if hint is int:
            if not number.is_integer() or abs(number) > 1e18:
                return " (an integer field takes whole numbers, written as digits, e.g. 3)"
            return f" (YAML reads it as text: write {int(number)}, digits without quotes)"
        return f" (YAML reads it as text: write {number!r})"
    return ""


# The SI prefixes a number given with a unit may carry, as powers of ten.
_PREFIXES = {"": 0, "k": 3, "c": -2, "m": -3, "u": -6, "\u00b5": -6, "n": -9}
_NUMBER_WITH_UNIT = re.compile(r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S.*)")


def _unit_converted(number: str, written: str, unit: str) -> float | None:
    """`number` given in `written` as a number in `unit` when both are one unit with SI
    prefixes (150 in g as 0.15 kg, 15 in mm as 0.015 m), else None."""
    for base in (unit, unit[1:] if unit[:1] in _PREFIXES else ""):
        prefix = written[:-len(base)] if base and written.endswith(base) else None
        if prefix in _PREFIXES:
            power = _PREFIXES[prefix] - _PREFIXES[unit[:-len(base)]]
            converted = float(number) * 10.0 ** power  # None: beyond a float's range
            fits = math.isfinite(converted) and bool(converted) == bool(float(number))
            return converted if fits else None
    return None


def _unit_hint(value: str, unit: str) -> str:
    """How to write `value`, a number with a unit, in a field declared in `unit` ("" for
    none, or for other text)."""
    given = _NUMBER_WITH_UNIT.fullmatch(value.strip())
    if not unit or given is None:
        return ""
    number = _unit_converted(*given.groups(), unit)
    if number is None:
        return f" (the field is in {unit}: write the number in {unit}, without a unit)"
    return f" (the field is in {unit} and takes a bare number: write {number_text(number)})"


def _union_member(value, members, path: str, source: str):
    """The member of a Union that a YAML tag (or its absence: the first) selects."""
    tag = value.get("_tag") if isinstance(value, dict) else None
    if tag is None:
        return members[0], value
    for member in members:
        if tag == f"!{member.__name__}":
            return member, {k: v for k, v in value.items() if k != "_tag"}
    known = ", ".join(f"!{m.__name__}" for m in members)
    raise ConfigError(f"{source}: field '{path}': unknown tag {tag} (known: {known})")


def _field(path: str) -> str:
    return f"field '{path}' " if path else ""


def _describe(value) -> str:
    from tegrasp_drake.rig.echo import given
    return given(value)
