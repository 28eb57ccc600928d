"""The public API's boundary: `@public_api` checks a public function's arguments
against their annotations at the call and names the wrong one (classes, unions, the items
of collections, Callable; text is never a collection), then a config argument's fields
(their types, and the ranges and choices declared on them, as where a config is loaded),
then the `typing.Annotated` constraints declared beside them: a Range or Choice
(rig/ranges.py), a Folder."""

import collections.abc
import contextlib
import dataclasses
import difflib
import functools
import inspect
import os
import pathlib
import re
import threading
import types
import typing

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.rig.echo import given, shown
from tegrasp_drake.rig.ranges import check_ranges, number_problem, python_scalar

# A file or folder argument: text or a path object (pathlib.Path, os.DirEntry).
PathLike = str | os.PathLike

_TEXT = (str, bytes, bytearray)
_ITEM_CHECKED = (list, tuple, collections.abc.Sequence, collections.abc.Collection,
                 collections.abc.Set, set, frozenset)


@dataclasses.dataclass(frozen=True)
class TextPattern:
    """A text argument that must match `pattern` (a compiled regular expression): `words`
    say what it must be, following "argument 'x'"."""
    pattern: re.Pattern
    words: str


@dataclasses.dataclass(frozen=True)
class Folder:
    """A folder argument: `exists`, already there; `writable`, this user can write in or make."""
    exists: bool = True
    writable: bool = False

    def problem(self, path) -> str | None:
        """Why `path` is not such a folder, in words that follow it, or None."""
        from tegrasp_drake.rig.files import folder_problem
        if not os.fspath(path).strip():  # not the current folder: as the CLI's --out
            return "is empty; give a folder"
        path = pathlib.Path(path)
        try:  # not path.exists(): it reads a symlink loop as missing
            os.stat(path)
            there = True
        except (FileNotFoundError, NotADirectoryError):
            there = False
        except OSError as e:  # a name too long, a symlink loop
            return f"cannot be used ({os_error_text(e)})"
        if not there:
            if self.exists:
                return "does not exist; give an existing folder"
        elif not path.is_dir():
            what = "a file" if path.is_file() else "a device, pipe or socket"
            return f"is {what}, not a folder; give a folder"
        if self.writable:
            problem = folder_problem(path)
            if problem:
                return f"cannot be written ({problem}); give a folder you can write"
        return None


INPUT_FOLDER = Folder(exists=True)                    # read from
OUTPUT_FOLDER = Folder(exists=False, writable=True)   # written to, made if need be
UPDATED_FOLDER = Folder(exists=True, writable=True)   # read from and written to
SEARCHED_FOLDER = Folder(exists=False)                # read from if there (a search path's)


# A config class's method (source) -> None that raises ConfigError naming the field unless
# its fields relate as a loaded one's must (an object's sizes for its shape, the arm's start
# in reach: what a field's type and range cannot say); public_api calls it on each argument
# of that class, so a config changed after loading is refused before a function uses it.
RELATIONS_CHECK = "check_relations"


class _RelationsCheck(threading.local):
    active = False  # a relations check runs in this thread


_checking_relations = _RelationsCheck()


@contextlib.contextmanager
def relations_checked():
    """The block checks a config's relations (a validate): the public functions it calls
    do not check the same config's relations again (which would recurse)."""
    outer = _checking_relations.active
    _checking_relations.active = True
    try:
        yield
    finally:
        _checking_relations.active = outer


def public_api(function):
    """Wraps `function` so that each call checks its arguments (module docstring)."""
    signature = inspect.signature(function)
    hints = None
    # How errors name it: a constructor by its class ("EventMatcher: argument 'events'").
    name = function.__qualname__.removesuffix(".__init__").split(".<locals>.")[-1]

    @functools.wraps(function)
    def checked(*args, **kwargs):
        nonlocal hints
        if hints is None:  # resolved at the first call: annotations may name later classes
            hints = typing.get_type_hints(function, include_extras=True)
        try:
            bound = signature.bind(*args, **kwargs)
        except TypeError as e:
            raise TypeError(f"{name}: {e}") from None
        _check_bound(name, signature, hints, bound)
        return function(*bound.args, **bound.kwargs)  # NumPy scalars as Python's numbers

    def bind_now(**kwargs):
        """functools.partial(function, **kwargs) with those arguments checked now, not at
        each later call (a sweep's trial function, called in its workers)."""
        nonlocal hints
        if hints is None:
            hints = typing.get_type_hints(function, include_extras=True)
        try:
            bound = signature.bind_partial(**kwargs)
        except TypeError as e:
            raise TypeError(f"{name}: {e}") from None
        _check_bound(name, signature, hints, bound)
        return functools.partial(checked, **bound.kwargs)

    checked.bind_now = bind_now
    checked.__checked_arguments__ = True
    return checked


def _check_bound(name: str, signature, hints: dict, bound) -> None:
    """Checks the arguments in `bound` (types, configs' fields and relations, constraints),
    naming function `name` and the argument; a NumPy scalar argument, or one in a list or
    tuple argument, is replaced in `bound` by the Python number it holds (python_numbers)."""
    for argument, value in list(bound.arguments.items()):
        bound.arguments[argument] = python_numbers(value)
    for argument, value in bound.arguments.items():
        hint = hints.get(argument)
        if hint is None:
            continue
        hint, _ = _constraints(hint)
        parameter = signature.parameters[argument]
        if parameter.kind is parameter.VAR_POSITIONAL:
            values = value
        elif parameter.kind is parameter.VAR_KEYWORD:
            values = value.values()
        else:
            values = (value,)
        for item in values:
            if not _matches(item, hint):
                where, expected, wrong = _mismatch(argument, item, hint)
                raise TypeError(f"{name}: argument '{where}' must be "
                                f"{_describe_hint(expected, wrong)}, got {given(wrong)}")
    for argument, value in bound.arguments.items():  # a config's fields, changed since?
        if _mutable_dataclass(value):
            from tegrasp_drake.rig.typed_yaml import check_instance
            check_instance(value, f"{name}: argument '{argument}'")
            if _checking_relations.active:
                continue  # a part of a config being checked: its check names the config
            relations = getattr(value, RELATIONS_CHECK, None)  # what relates its fields
            if relations is None:  # its declared ranges and choices, as the loader checks
                check_ranges(value, f"{name}: argument '{argument}'")
                continue
            with relations_checked():  # its own public calls: not again
                relations(f"{name}: {argument}")  # its ranges too, as the builders' rechecked
    for argument, value in bound.arguments.items():  # every type is right: the values
        _check_path_text(name, argument, value, hints.get(argument))
        constraints = _constraints(hints.get(argument))[1]
        if not any(isinstance(c, Folder) for c in constraints):  # a Folder says it itself
            _check_path_given(name, argument, value, hints.get(argument),
                              signature.parameters[argument].default)
        for constraint in constraints:
            _check_constraint(name, argument, value, constraint)


def _takes_path(hint) -> bool:
    """Whether `hint` (PathLike, PathLike | None, Annotated[...]) takes a file or folder name."""
    hint = _constraints(hint)[0]
    if hint is os.PathLike:
        return True
    return any(_takes_path(member) for member in typing.get_args(hint)
               if typing.get_origin(hint) in (typing.Union, types.UnionType))


def _check_path_text(function: str, name: str, value, hint) -> None:
    """UserPathError when a file or folder name argument (a PathLike one, with or without a
    Folder constraint) holds a NUL byte, which no operating system takes in a path (its
    readers would fail with a bare "embedded null byte"), naming the argument and the
    byte's position."""
    if not (isinstance(value, (str, os.PathLike)) and _takes_path(hint)):
        return
    text = os.fspath(value)
    position = text.find(b"\0" if isinstance(text, bytes) else "\0")
    if position < 0:
        return
    from tegrasp_drake.rig.files import UserPathError
    what = "folder" if name.endswith(("_dir", "folder")) else "file"
    raise UserPathError(f"{function}: argument '{name}' holds a NUL byte at position "
                        f"{position} ({shown(text)}): no {what} name can hold one; "
                        "remove it")


def _check_path_given(function: str, name: str, value, hint, default) -> None:
    """UserPathError when a file name argument (a PathLike one) is the empty text: never read
    as "not given" (a default file) nor as the current folder; the command line's words for
    an empty file option (`--scenario '' is empty; give ...`), "a folder" for an argument
    named *_dir or *folder. Text of spaces is a name, as
    on the command line: its reader says it does not exist."""
    if not (isinstance(value, str) and value == "" and _takes_path(hint)):
        return
    from tegrasp_drake.rig.files import UserPathError
    what = "a folder" if name.endswith(("_dir", "folder")) else "a file"
    default_words = ", or None for its default" if default is None else ""
    raise UserPathError(f"{function}: argument '{name}': '' is empty; give {what}"
                        f"{default_words}")


def _mismatch(where: str, value, hint) -> tuple:
    """(where, hint, value) of what in `value` is not of `hint`: the first wrong item of a
    list or tuple of the hint's kind (`overrides[0]`), or of a mapping's under a key of the
    right type (`window_states['sa']`), else the value itself."""
    members = typing.get_args(hint) if typing.get_origin(hint) in (
        typing.Union, types.UnionType) else (hint,)
    for member in members:
        member = _constraints(member)[0]
        origin, arguments = typing.get_origin(member), typing.get_args(member)
        if (isinstance(value, (list, tuple)) and isinstance(origin, type)
                and isinstance(value, origin) and arguments
                and arguments[1:] in ((), (Ellipsis,))):
            for k, item in enumerate(value):
                if not _matches(item, arguments[0]):
                    return _mismatch(f"{where}[{k}]", item, arguments[0])
        if (isinstance(value, collections.abc.Mapping) and isinstance(origin, type)
                and issubclass(origin, collections.abc.Mapping) and len(arguments) == 2):
            for key, item in value.items():
                if _matches(key, arguments[0]) and not _matches(item, arguments[1]):
                    return _mismatch(f"{where}[{shown(key)}]", item, arguments[1])
    return where, hint, value


def python_numbers(value):
    """`value` with NumPy scalars as the Python numbers they hold (python_scalar): the value
    itself, or a list or tuple's items (a new list or tuple, only if one is a NumPy scalar).
    The API takes np.float32(0.2) as the number 0.2 and keeps it as one: a NumPy scalar kept
    in a config or a result would reach what cannot write it (JSON: "int64 is not JSON
    serializable") long after the call that gave it."""
    if isinstance(value, (list, tuple)) and any(_numpy_scalar(item) for item in value):
        items = [python_scalar(item) for item in value]
        return items if isinstance(value, list) else (
            type(value)(*items) if hasattr(value, "_fields") else type(value)(items))
    return python_scalar(value) if _numpy_scalar(value) else value


def array_problem(array, expected_shape: tuple[int, ...]) -> str | None:
    """Why the NumPy array `array` (a public dataclass's array field, of type ndarray as its
    type check asks) cannot be an array of real numbers of `expected_shape`, in words that
    follow its name, or None; read from its `shape` and `dtype` (free on an ndarray) before
    any conversion, so that a 100-million-row array is refused without a copy."""
    if array.dtype.kind not in "biuf":
        return f"holds {array.dtype} values, not real numbers"
    if tuple(array.shape) != tuple(expected_shape):
        return f"has shape {tuple(array.shape)}"
    return None


def _numpy_scalar(value) -> bool:
    """A NumPy number or bool, as a scalar or a 0-d array (one python_scalar converts)."""
    return (type(value).__module__ == "numpy" and getattr(value, "ndim", None) == 0
            and getattr(getattr(value, "dtype", None), "kind", "") in "biuf")


def bound_arguments(function, **kwargs):
    """functools.partial(function, **kwargs), the arguments checked now when `function` is
    a public one (public_api): a bad folder is refused before a sweep runs its trials."""
    bind_now = getattr(function, "bind_now", None)
    return bind_now(**kwargs) if bind_now is not None else functools.partial(function, **kwargs)


def _constraints(hint) -> tuple:
    """(the type of `hint`, the constraints its Annotated metadata declares)."""
    if hint is None or typing.get_origin(hint) is not typing.Annotated:
        return hint, ()
    from tegrasp_drake.rig.ranges import Choice, Range
    return hint.__origin__, tuple(m for m in hint.__metadata__
                                  if isinstance(m, (Range, Choice, Folder, TextPattern)))


def check_argument(function: str, name: str, value, constraint) -> None:
    """Raises naming `function`'s argument `name` when `value` breaks `constraint` (a Range,
    Choice or Folder known only at the call, e.g. from another argument), in the words of
    the declared ones."""
    _check_constraint(function, name, value, constraint)


def _check_constraint(function: str, name: str, value, constraint) -> None:
    """Raises naming `function`'s argument `name` when `value` breaks `constraint`."""
    from tegrasp_drake.rig.ranges import Choice
    if value is None:
        return  # None passed the type check: "not given"
    where = f"{function}: argument '{name}'"
    if isinstance(constraint, Folder):
        problem = constraint.problem(value)
        if problem:
            from tegrasp_drake.rig.files import UserPathError
            raise UserPathError(f"{where}: {os.fspath(value)!r} {problem}")
    elif isinstance(constraint, TextPattern):
        if not isinstance(value, str) or not constraint.pattern.match(value):
            raise ValueError(f"{where} {constraint.words}, got {shown(value)}")
    elif isinstance(constraint, Choice):
        if value not in constraint.names:
            raise ValueError(f"{where} {constraint.words()}, got {shown(value)}")
    else:  # a Range: of the number, or of each number of a sequence
        items = value if isinstance(value, (list, tuple)) else (value,)
        for k, item in enumerate(items):
            at = where if items is not value else f"{where}[{k}]"
            if not isinstance(item, (int, float)) or isinstance(item, bool):
                continue  # the type check said what the items may be
            problem = number_problem(item)
            if problem is not None:
                raise ValueError(f"{at} {problem}")
            if not constraint.contains(item):
                raise ValueError(f"{at} {constraint.words(item)}, got {item!r}")


def value_matches(value, hint) -> bool:
    """Whether `value` is of the type `hint` by the rules of a public function's arguments."""
    return _matches(value, hint)


def describe_hint(hint) -> str:
    """The type `hint` in words, as an argument error says it."""
    return _describe_hint(hint)


def _matches(value, hint) -> bool:
    if hint is typing.Any or hint is object:
        return True
    if hint is None or hint is type(None):
        return value is None
    origin = typing.get_origin(hint)
    if origin is typing.Annotated:
        return _matches(value, hint.__origin__)
    if origin in (typing.Union, types.UnionType):
        return any(_matches(value, member) for member in typing.get_args(hint))
    if origin is typing.Literal:
        return value in typing.get_args(hint)
    if origin is None:
        if hint is float:
            return isinstance(value, (int, float)) and not isinstance(value, bool)
        if hint is int:
            return isinstance(value, int) and not isinstance(value, bool)
        if isinstance(hint, typing.TypeVar) or not isinstance(hint, type):
            return True  # a TypeVar, a string left unresolved: not checked
        return isinstance(value, hint)
    if origin is collections.abc.Callable:
        return callable(value)
    if not isinstance(value, origin):
        return False
    if isinstance(value, _TEXT) and origin not in (str, bytes):
        return False  # text where a collection is expected
    arguments = typing.get_args(hint)
    items_checked = issubclass(origin, _ITEM_CHECKED) or (
        origin is collections.abc.Iterable and isinstance(value, collections.abc.Collection))
    if issubclass(origin, collections.abc.Mapping):
        return len(arguments) != 2 or all(
            _matches(key, arguments[0]) and _matches(item, arguments[1])
            for key, item in value.items())
    if not arguments or not items_checked:
        return True
    if origin is tuple and not (len(arguments) == 2 and arguments[1] is Ellipsis):
        return len(value) == len(arguments) and all(
            _matches(item, member) for item, member in zip(value, arguments))
    return all(_matches(item, arguments[0]) for item in value)


_UNKNOWN = object()  # _describe_hint's `given` when no value is at hand


def _collection_qualifier(given, item_hint) -> str:
    """What to say after "a sequence of X" (X: `item_hint`) to the value `given` in its
    place: a string or a mapping is the usual slip (the list's one item; a dict of the
    items, whose values are what to give when they are of X)."""
    if given is _UNKNOWN or isinstance(given, _TEXT):
        return " (not a single string)"
    if isinstance(given, collections.abc.Mapping):
        if given and item_hint is not None and all(_matches(v, item_hint)
                                                   for v in given.values()):
            return " (not a mapping: give its values, list(d.values()))"
        return " (not a mapping)"
    return ""


def _describe_hint(hint, given=_UNKNOWN) -> str:
    """What a value of type `hint` is, in words; `given`, the wrong value, picks the
    qualifier a collection gets (_collection_qualifier)."""
    origin = typing.get_origin(hint)
    if origin is typing.Annotated:
        return _describe_hint(hint.__origin__, given)
    if origin in (typing.Union, types.UnionType):
        return " or ".join(_describe_hint(member, given) for member in typing.get_args(hint))
    if hint is type(None) or hint is None:
        return "None"
    if origin is None:
        return getattr(hint, "__name__", str(hint))
    arguments = typing.get_args(hint)
    name = getattr(origin, "__name__", str(origin))
    if name in ("Sequence", "Collection", "list", "Iterable", "Set", "set", "frozenset"):
        items = _describe_hint(arguments[0]) if arguments else "values"
        article = "an" if name[0] in "AEIOUaeiou" else "a"
        qualifier = _collection_qualifier(given, arguments[0] if arguments else None)
        return f"{article} {name.lower()} of {items}{qualifier}"
    if name == "tuple" and arguments and Ellipsis not in arguments:  # tuple[float, float]
        return (f"a tuple of {len(arguments)} ("
                f"{', '.join(_describe_hint(member) for member in arguments)})"
                f"{_collection_qualifier(given, None)}")
    # Class names without their modules: Mapping[str, MemorizedEvent].
    return re.sub(r"\b(?:[a-z_]\w*\.)+([A-Za-z_]\w*)", r"\1", str(hint))


def public_dataclass(cls):
    """Class decorator (above @dataclass): the constructor refuses a value not of its field's
    type where that is str, int, float or bool (or optional: `hold_success='yes'`), and a
    text string in a field annotated as a collection (`objects='box'` for `tuple[str, ...]`),
    naming class and field (check_field_types, which a __post_init__ that reads its fields'
    values calls first). A keyword argument or an attribute that is not a field is refused
    naming the class and what to write (the field a moved setting is now, what replaced a
    removed one, the closest field name); assigning a field of a frozen class, in one line
    saying how to make a changed copy (FrozenFieldError). A NumPy scalar given for a field, at
    construction or assigned, is kept as the Python number it holds (python_numbers)."""
    init = cls.__init__
    parameters = inspect.signature(init).parameters
    if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters.values()):
        parameters = None  # an __init__ of its own that takes any keyword

    @functools.wraps(init)
    def checked_init(self, *args, **kwargs):
        unknown = next((name for name in kwargs if parameters is not None
                        and name not in parameters), None)
        if unknown is not None:  # a misspelt, moved or removed setting: say which, in one line
            raise TypeError(_no_such_field(cls, unknown))
        init(self, *args, **kwargs)
        if type(self) is cls:  # a subclass's own fields are its own decorator's
            for field in dataclasses.fields(cls):  # NumPy scalars: python_numbers
                value = getattr(self, field.name)
                if python_numbers(value) is not value:
                    object.__setattr__(self, field.name, python_numbers(value))
            check_field_types(self)

    cls.__init__ = checked_init
    cls.__init__.__checked_arguments__ = True
    if cls.__dataclass_params__.frozen:
        cls.__setattr__ = _refuse_change
        cls.__delattr__ = _refuse_change
    else:
        cls.__setattr__ = _set_field_only
    return cls


@functools.cache
def _typed_fields(cls) -> tuple[list, object]:
    """(the fields of `cls` annotated as collections, its scalar fields)."""
    try:
        hints = typing.get_type_hints(cls)
    except Exception:  # noqa: BLE001: an annotation typing cannot resolve
        hints = {f.name: f.type for f in dataclasses.fields(cls) if not isinstance(f.type, str)}
    return ([name for name in getattr(cls, "__dataclass_fields__", {})
             if _expects_collection(hints.get(name))], _scalar_fields(cls, hints))


def check_field_types(instance) -> None:
    """ConfigTypeError naming the first field of a public dataclass `instance` not of its type: a
    scalar field (str, int, float, bool), a collection given as one string or as an array
    (numpy's), then nested configs, enums, arrays and items (typed_yaml.check_instance)."""
    cls = type(instance)
    collections_, scalar = _typed_fields(cls)
    _check_scalar_fields(instance, scalar, cls.__name__)
    for name in collections_:
        value = getattr(instance, name)
        if isinstance(value, _TEXT):
            from tegrasp_drake.rig.typed_yaml import ConfigTypeError
            raise ConfigTypeError(f"{cls.__name__}: field '{name}' must be a collection "
                            f"(not a single string), got {type(value).__name__} "
                            f"{shown(value)}; e.g. {name}=[{shown(value)}]")
        if hasattr(value, "__array__") and not isinstance(value, (list, tuple)):
            from tegrasp_drake.rig.typed_yaml import ConfigTypeError, array_for_list_words
            raise ConfigTypeError(f"{cls.__name__}: field '{name}' "
                            f"{array_for_list_words(value, name)}")
    from tegrasp_drake.rig.typed_yaml import check_instance
    check_instance(instance, cls.__name__)  # nested configs, enums, arrays, items


class FrozenFieldError(dataclasses.FrozenInstanceError):
    """A field of a frozen public dataclass assigned or deleted (a FrozenInstanceError, as
    the dataclass's own, so code that catches that still does)."""


@functools.cache
def _field_names(cls) -> frozenset:
    """The names of the fields of dataclass `cls` (dataclasses.fields: not its ClassVars)."""
    return frozenset(field.name for field in dataclasses.fields(cls))


def _set_field_only(self, name: str, value) -> None:
    """Assigns a field; an attribute that is not one (a misspelt or moved setting, or a
    ClassVar, which would otherwise be kept and ignored) is an AttributeError naming its class
    and what to write."""
    if name not in _field_names(type(self)) and not name.startswith("_"):
        raise AttributeError(_no_such_field(type(self), name))
    object.__setattr__(self, name, python_numbers(value))


def _refuse_change(self, name: str, value=None) -> None:
    """A frozen public dataclass's __setattr__ and __delattr__: FrozenFieldError, for a field
    saying how to make a changed copy, else naming the class's fields as _set_field_only does."""
    cls = type(self)
    if name not in _field_names(cls):
        raise FrozenFieldError(_no_such_field(cls, name))
    # What to call the instance in the advice: its class name's last word (TrialResult: result).
    instance = re.findall(r"[A-Z]?[a-z0-9]+|[A-Z]+(?![a-z])", cls.__name__)[-1].lower()
    raise FrozenFieldError(f"{cls.__name__}.{name} cannot be changed: make a changed copy with "
                           f"dataclasses.replace({instance}, {name}=...)")


def _no_such_field(cls, name: str) -> str:
    """'<cls> has no field '<name>': <advice>', the advice the field it moved to, else the
    closest field name, else the list of fields; for a removed field, what replaced it."""
    fields = sorted(_field_names(cls), key=list(cls.__dataclass_fields__).index)
    if name in cls.__dataclass_fields__:  # a ClassVar: the class's, the same for every instance
        return (f"{cls.__name__}.{name} belongs to the class ({shown(getattr(cls, name))}), "
                "not to an instance: it cannot be set; choose the class that has the value "
                "you want")
    removed = getattr(cls, "__removed_fields__", {}).get(name)
    if removed:  # the words of the scenario's refusal (scenario/moved_keys.py)
        return f"{cls.__name__}: field '{name}' was removed: {removed}; leave it out"
    moved = getattr(cls, "__moved_fields__", {}).get(name)
    if moved:
        advice = f"it is now '{moved}'"
    else:
        close = difflib.get_close_matches(name, fields, n=1)
        advice = f"did you mean '{close[0]}'?" if close else f"its fields: {', '.join(fields)}"
    return f"{cls.__name__} has no field '{name}': {advice}"


def register_moved_fields(cls, moved: dict[str, str]) -> None:
    """Names, for a public dataclass's refused attributes, the new paths of settings that
    moved (old field name -> new dotted path relative to the instance)."""
    cls.__moved_fields__ = dict(moved)


def register_removed_fields(cls, removed: dict[str, str]) -> None:
    """Names, for a public dataclass's refused keyword arguments and attributes, what replaced
    the settings a version removed (old field name -> what took its place)."""
    cls.__removed_fields__ = dict(removed)


def check_field_values(instance, source: str | None = None) -> None:
    """Checks a dataclass instance's fields as public_api checks arguments: TypeError for the first
    field not of its (scalar) type, then ConfigError for the first number outside its range."""
    from tegrasp_drake.rig.ranges import check_ranges
    cls = type(instance)
    _check_scalar_fields(instance, _scalar_fields(cls, typing.get_type_hints(cls)),
                         source or cls.__name__)
    from tegrasp_drake.rig.typed_yaml import check_instance
    check_instance(instance, source or cls.__name__)
    check_ranges(instance, source or cls.__name__)


def _mutable_dataclass(value) -> bool:
    """A dataclass instance whose fields may have been set since it was built and checked."""
    return (dataclasses.is_dataclass(value) and not isinstance(value, type)
            and not type(value).__dataclass_params__.frozen)


def _scalar_fields(cls, hints: dict) -> dict:
    """{name: annotation} of `cls`'s fields annotated as str, int, float or bool (or an
    optional one): the fields a public dataclass checks at construction."""
    scalar = {}
    for field in dataclasses.fields(cls):
        hint = hints.get(field.name)
        if typing.get_origin(hint) not in (None, typing.Union, types.UnionType):
            continue  # a collection: public_api's item checks are for arguments
        members = [m for m in (typing.get_args(hint) or (hint,)) if m is not type(None)]
        if members and all(m in (str, int, float, bool) for m in members):
            scalar[field.name] = hint
    return scalar


def _check_scalar_fields(instance, scalar: dict, source: str) -> None:
    """ConfigTypeError (a ConfigError and a TypeError, as every config field's wrong type)
    naming the first of the `scalar` fields whose value is not of its type (a NumPy scalar
    counts as the Python one it holds: np.bool_ as bool)."""
    for name, hint in scalar.items():
        value = getattr(instance, name)
        if not _matches(python_scalar(value), hint):
            from tegrasp_drake.rig.typed_yaml import ConfigTypeError
            raise ConfigTypeError(f"{source}: field '{name}' must be {_describe_hint(hint)}, "
                                  f"got {given(value)}")


def _expects_collection(hint) -> bool:
    """True for an annotation that takes only collections (tuple[...], list[...], Sequence)."""
    if hint is None:
        return False
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        members = [m for m in typing.get_args(hint) if m is not type(None)]
        return bool(members) and all(_expects_collection(m) for m in members)
    return (origin is not None and isinstance(origin, type)
            and issubclass(origin, _ITEM_CHECKED) and not issubclass(origin, _TEXT))
