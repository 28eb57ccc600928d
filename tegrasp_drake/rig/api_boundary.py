"""The public API's boundary: a function of `tegrasp_drake.__all__` checks its arguments
against its annotations when it is called, and names the wrong one.

    @public_api
    def LoadScenario(filename: str | os.PathLike | None = None, name: str = "default", ...):

`LoadScenario(name=None)` then raises `TypeError: LoadScenario: argument 'name' must be str,
got NoneType None` at the call, instead of an AttributeError deep inside. What is checked:
classes (an int is a float; a bool is neither an int nor a float), `X | Y` and Optional,
`list[T]`, `tuple[T, ...]` and `tuple[A, B]`, `Sequence[T]` and `Collection[T]` (their items
too), `Iterable[T]` (its items when it is a collection such as a list; a one-shot iterator
is not consumed: only that it is iterable), `Mapping`/`dict`, `Callable`;
a text string is never taken where a collection is expected (it would be iterated as
characters). An unannotated parameter, or one annotated `typing.Any`, is not checked; a test
(tests/test_bad_input_disciplines.py) holds every public function to annotating all of them.
"""

import collections.abc
import dataclasses
import functools
import inspect
import os
import types
import typing

# A file or folder argument: text or a path object (pathlib.Path, os.DirEntry).
PathLike = str | os.PathLike

_TEXT = (str, bytes, bytearray)
_ITEM_CHECKED = (list, tuple, collections.abc.Sequence, collections.abc.Collection,
                 collections.abc.Set, set, frozenset)


def public_api(function):
    """Wraps `function` so that each call checks its arguments (module docstring)."""
    signature = inspect.signature(function)
    hints = None

    @functools.wraps(function)
    def checked(*args, **kwargs):
        nonlocal hints
        if hints is None:  # resolved at the first call: annotations may name later classes
            hints = typing.get_type_hints(function)
        try:
            bound = signature.bind(*args, **kwargs)
        except TypeError as e:
            raise TypeError(f"{function.__name__}: {e}") from None
        for name, value in bound.arguments.items():
            hint = hints.get(name)
            if hint is None:
                continue
            parameter = signature.parameters[name]
            if parameter.kind is parameter.VAR_POSITIONAL:
                values = value
            elif parameter.kind is parameter.VAR_KEYWORD:
                values = value.values()
            else:
                values = (value,)
            for item in values:
                if not _matches(item, hint):
                    raise TypeError(f"{function.__name__}: argument '{name}' must be "
                                    f"{_describe_hint(hint)}, got {type(item).__name__} "
                                    f"{_short_repr(item)}")
        return function(*args, **kwargs)

    checked.__checked_arguments__ = True
    return checked


def _matches(value, hint) -> bool:
    if hint is typing.Any or hint is object:
        return True
    if hint is None or hint is type(None):
        return value is None
    origin = typing.get_origin(hint)
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
    if not arguments or not items_checked or issubclass(origin, collections.abc.Mapping):
        return True
    if origin is tuple and not (len(arguments) == 2 and arguments[1] is Ellipsis):
        return len(value) == len(arguments) and all(
            _matches(item, member) for item, member in zip(value, arguments))
    return all(_matches(item, arguments[0]) for item in value)


def _describe_hint(hint) -> str:
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        return " or ".join(_describe_hint(member) for member in typing.get_args(hint))
    if hint is type(None) or hint is None:
        return "None"
    if origin is None:
        return getattr(hint, "__name__", str(hint))
    arguments = typing.get_args(hint)
    name = getattr(origin, "__name__", str(origin))
    if name in ("Sequence", "Collection", "list", "Iterable", "Set", "set", "frozenset"):
        items = _describe_hint(arguments[0]) if arguments else "values"
        article = "an" if name[0] in "AEIOUaeiou" else "a"
        return f"{article} {name.lower()} of {items} (not a single string)"
    return str(hint).replace("typing.", "").replace("collections.abc.", "")


def _short_repr(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def public_dataclass(cls):
    """Class decorator (above @dataclass) for a public dataclass a user builds by hand: its
    constructor refuses a text string in a field annotated as a collection (`objects='box'`
    where `objects: tuple[str, ...]` is meant; it would be iterated as characters), naming
    the class and field."""
    init = cls.__init__
    fields = None

    @functools.wraps(init)
    def checked_init(self, *args, **kwargs):
        nonlocal fields
        init(self, *args, **kwargs)
        if fields is None:
            try:
                hints = typing.get_type_hints(cls)
            except Exception:  # noqa: BLE001: an annotation typing cannot resolve
                hints = {f.name: f.type for f in dataclasses.fields(cls)
                         if not isinstance(f.type, str)}
            fields = [name for name in getattr(cls, "__dataclass_fields__", {})
                      if _expects_collection(hints.get(name))]
        for name in fields:
            value = getattr(self, name)
            if isinstance(value, _TEXT):
                raise TypeError(f"{cls.__name__}: field '{name}' must be a collection "
                                f"(not a single string), got {type(value).__name__} "
                                f"{_short_repr(value)}; e.g. {name}=[{_short_repr(value)}]")

    cls.__init__ = checked_init
    cls.__init__.__checked_arguments__ = True
    return cls


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
