"""Every numeric setting's unit and allowed range, declared once beside the field
(`hold_s: float = bounded(3.0, low=0.0, high=60.0, unit="s", why=...)`), and every text
setting's allowed names (`chosen("fifo", names=(...))`). `check_ranges` walks a config where
it is loaded and where a builder is handed one, and raises a one-line ConfigError for the
first value outside its range or choice."""

import collections.abc
import dataclasses
import math
import types
import typing

from tegrasp_drake.rig.integer_text import integer_beyond_problem
from tegrasp_drake.rig.echo import given, shown
from tegrasp_drake.rig.number_text import number_text

_KEY = "tegrasp_range"
_LENGTH_KEY = "tegrasp_length"
_DISTINCT_KEY = "tegrasp_distinct"  # a list of names, each at most once
_SETTINGS_KEY = "tegrasp_settings"  # a list of KEY=VALUE settings (as --set), not names


@dataclasses.dataclass(frozen=True)
class Range:
    """[low, high] (an end None: unbounded; `low_open`/`high_open`: that end excluded) in
    `unit`; `why` says where the ends come from; `below` replaces the words for a value
    under `low` (a field's established message, e.g. "must be positive [kg]")."""
    low: float | None = None
    high: float | None = None
    unit: str = ""
    why: str = ""
    low_open: bool = False
    high_open: bool = False
    below: str | None = None
    length: int | None = None  # a list field: how many elements it holds

    def contains(self, value) -> bool:
        if value != value:  # nan: in no range (an open end would let it through)
            return False
        if self.low is not None and (value < self.low or (self.low_open and value == self.low)):
            return False
        return self.high is None or (value < self.high or (not self.high_open
                                                           and value == self.high))

    def words(self, value) -> str:
        return self._words(value).replace("{low}", _number(self.low)).replace(
            "{high}", _number(self.high))

    def _words(self, value) -> str:
        """What the value must be, e.g. "must lie in [0, 60] s (why)"."""
        if self.below is not None and self.low is not None and (
                value < self.low or (self.low_open and value == self.low)):
            return self.below
        unit = f" {self.unit}" if self.unit else ""
        why = f" ({self.why})" if self.why else ""
        if self.high is None:
            return f"must be {'above' if self.low_open else 'at least'} {{low}}{unit}{why}"
        if self.low is None:
            return f"must be {'below' if self.high_open else 'at most'} {{high}}{unit}{why}"
        return (f"must lie in {'(' if self.low_open else '['}{{low}}, {{high}}"
                f"{')' if self.high_open else ']'}{unit}{why}")


# A real-time run on the devices [s] (`tegrasp hardware --duration`, run_on_hardware's duration):
# the grasp takes about 12 s; ten minutes leaves room for a slow hand-held test without a typo
# (a 1e7) holding the devices for days.
HARDWARE_RUN_DURATION = Range(low=0.0, low_open=True, high=600.0, unit="s",
                              why="a grasp takes about 12 s; at most ten minutes on the devices")


# When an emulated device fault is injected [s after the gripper's activation] (`tegrasp
# emulate --inject-fault CODE@SECONDS`): within a hardware run, which lasts at most
# HARDWARE_RUN_DURATION; a later fault would never be seen.
FAULT_DELAY = Range(low=0.0, high=HARDWARE_RUN_DURATION.high, unit="s",
                    why="after the gripper's activation, within a hardware run's ten minutes")


# The slowest tactile sampling the event windows allow [Hz]: a 0.5 s window (Sec. III-A) of
# fewer than 8 samples has no shape for Eq. 3 to compare. The low end of the sensors' sample
# rates, of the rates the EventMatcher and a memorized event are sampled at, and of the arm's
# command rate (a reaction decided on a tactile sample reaches the arm before the next one).
EVENT_WINDOW_RATE_LOW_HZ = 16.0
EVENT_WINDOW_RATE_WHY = "a 0.5 s event window needs 8 samples"

# The fastest tactile sampling [Hz]: the films are integrated at 20 kHz (simulation/
# film_dynamics.py); the high end of the sensors' sample rates and of the rates the
# EventMatcher, the WindowNormalizer and a memorized event are sampled at (a window's
# samples are allocated: at 1 GHz a 0.5 s window would be gigabytes).
EVENT_WINDOW_RATE_HIGH_HZ = 20_000.0
SAMPLE_RATE_WHY = f"{EVENT_WINDOW_RATE_WHY}; the film is integrated at 20 kHz"
SAMPLE_RATE = Range(low=EVENT_WINDOW_RATE_LOW_HZ, high=EVENT_WINDOW_RATE_HIGH_HZ, unit="Hz",
                    why=SAMPLE_RATE_WHY)

# An event window [s] (Sec. III-A: 0.5 s), as the EventMatcher and the WindowNormalizer
# slide it and a memorized event holds it: its samples are allocated at each rate.
EVENT_WINDOW = Range(low=0.0, low_open=True, high=10.0, unit="s",
                     why="the paper's window is 0.5 s; a 10 s one spans a whole grasp")

# A block of film samples taken in one update [s] (tactile/sample_block.py; 0: one update per
# sample): the controller's sensor_block_s, the EventMatcher's and WindowNormalizer's block_s.
SAMPLE_BLOCK = Range(low=0.0, high=0.1, unit="s",
                     below="must be zero (one update per sample) or positive [s]")

# The tick of the one reader of the tactile samples [s] (tactile/read_batch.py; 0: read at
# each sample): the controller's update period reads them, at most 0.1 s.
READ_PERIOD = Range(low=0.0, high=0.1, unit="s",
                    why="the controller's tick, at most 0.1 s; 0: at each sample")

# A seed [-] (a scenario's random_seed, a sweep's base_seed, MakeGraspStation's random_seed).
SEED_RANGE = Range(low=0, high=2**32 - 1,
                   why="Drake's random generator takes a 32-bit seed; a larger one would repeat a "
                       "smaller one's noise")

# A simulated run's duration [s] (run_trial's max_time, run_ideal_grasp's duration): positive
# (Drake's simulator cannot advance to a time before its start); at most the scenario's time
# limit (grasp_diagram.simulated_duration_range), to which `tegrasp trial` runs.
SIMULATED_DURATION = Range(low=0.0, low_open=True, unit="s")


def option_problem(option: str, value, allowed: Range) -> str | None:
    """Why a command-line option's number `value` (one that parsed) is refused by its range
    `allowed`, in words naming the option (`--workers must be at least 1, got 0`); None if it
    lies in the range. A number that parses but lies outside its range is bad input (exit 1),
    not a command line that does not parse (exit 2). The value is echoed as the user typed it
    (echo.shown: `600.0001`, not 600)."""
    if allowed.contains(value):
        return None
    return f"{option} {allowed.words(value)}, got {shown(value)}"


def _number(value) -> str:
    """A range end as written (number_text), nothing for an open end."""
    return "" if value is None else number_text(value)


def bounded(default=dataclasses.MISSING, *, low=None, high=None, unit: str = "",
            why: str = "", low_open: bool = False, high_open: bool = False,
            below: str | None = None, default_factory=dataclasses.MISSING,
            length: int | None = None):
    """A dataclass field with the declared Range (module docstring); for a list field the
    range is each element's, and `length` how many elements it must hold."""
    return dataclasses.field(default=default, default_factory=default_factory, metadata={
        _KEY: Range(low, high, unit, why, low_open, high_open, below, length)})


def within(default, declared: Range):
    """A dataclass field taking the Range `declared` (one declared for several fields)."""
    return dataclasses.field(default=default, metadata={_KEY: declared})


def chosen(default, *, names: tuple[str | int, ...], why: str = ""):
    """A text field (or an integer one taking a few values, e.g. the AD7147's decimations)
    whose value must be one of `names` (a Choice; `why` says whose they are): checked by
    check_ranges with the numbers' Ranges, where a config is loaded and where a builder is
    handed one."""
    return dataclasses.field(default=default, metadata={_KEY: Choice(tuple(names), why)})


def declared_field(cls: type, name: str) -> dataclasses.Field:
    """A new field with the default and Range of `cls`'s field `name` (declared once)."""
    field = next(f for f in dataclasses.fields(cls) if f.name == name)
    return dataclasses.field(default=field.default, default_factory=field.default_factory,
                             metadata=field.metadata)


@dataclasses.dataclass(frozen=True)
class Choice:
    """A text (or integer) setting's allowed values; `why` says whose they are."""
    names: tuple[str | int, ...]
    why: str = ""

    def contains(self, value) -> bool:
        """Whether `value` is one of the names (as Range.contains for a number)."""
        return value in self.names

    def words(self) -> str:
        why = f" ({self.why})" if self.why else ""
        return f"must be one of {', '.join(repr(n) for n in self.names)}{why}"


# Ranges and choices of Drake's config classes: class -> {field: Range | Choice}.
_FOREIGN: dict[type, dict] = {}


def declare_ranges(cls: type, table: dict) -> None:
    """Declares Ranges or Choices of fields of `cls`, a Drake config class, for check_ranges."""
    _FOREIGN[cls] = dict(table)


def declared_ranges(cls: type) -> dict:
    """The table declare_ranges holds for `cls` ({} if none)."""
    return dict(_FOREIGN.get(cls, {}))


def range_of(field: dataclasses.Field) -> "Range | Choice | None":
    return field.metadata.get(_KEY)


def field_range(cls: type, name: str) -> Range:
    """The Range declared on the field `name` of `cls`, for a parameter taking its value."""
    declared = range_of(next(f for f in dataclasses.fields(cls) if f.name == name))
    if declared is None:
        raise LookupError(f"{cls.__name__}.{name} declares no range")
    return declared


def python_scalar(value):
    """A NumPy scalar as the Python one it holds (np.int64(3) -> 3, np.float32(0.2) -> 0.2 to
    float32's precision, np.longdouble as a float); other values unchanged."""
    if type(value).__module__ == "numpy" and getattr(value, "ndim", None) == 0:
        item = value.item()
        if type(item).__module__ == "numpy" and hasattr(item, "is_integer"):  # longdouble
            return float(item)
        return item
    return value


def real_number(value) -> int | float | None:
    """`value` as the Python number it is (a NumPy scalar of any real dtype as the int or
    float it holds: python_scalar), None if it is no number (a bool, text, an array, a
    complex number). Every check that asks whether a value is a number asks this, so that
    np.float32(0.2) is judged as 0.2, never refused as if it were not positive."""
    value = python_scalar(value)
    return value if _is_number(value) else None


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def number_problem(value) -> str | None:
    """Why `value` cannot be a setting's number, in words that follow "field 'x'": not a
    number, not finite (NaN, an infinity), or an integer beyond a float's range (the words
    the YAML and --set readers give its text); None for a finite number. Every range check
    asks this first, so that such a value is never judged, or refused, by its size."""
    value = python_scalar(value)
    if not _is_number(value):
        return f"must be a finite number, got {given(value)}"
    beyond = integer_beyond_problem(value)
    if beyond is not None:
        return beyond
    if not math.isfinite(value):
        return f"must be a finite number, got {type(value).__name__} {shown(value)}"
    return None


def is_integer(value) -> bool:
    """Whether `value` is a whole number as Python holds one (an int, not a bool: Python's True
    is the int 1, JSON's `true` is no number), for every field that must be an integer."""
    return isinstance(value, int) and not isinstance(value, bool)


def _values(value, path: str):
    """(path, number-or-other) of a scalar or of every leaf of nested lists/tuples, and of
    every value of a mapping (`path.key`: a map of names to times)."""
    if isinstance(value, (list, tuple)):
        for k, item in enumerate(value):
            yield from _values(item, f"{path}[{k}]")
    elif isinstance(value, collections.abc.Mapping):
        for key, item in value.items():
            yield from _values(item, f"{path}.{key}")
    else:
        yield path, value


def check_ranges(config, source: str, where: str = "", *, numbers_only: bool = False) -> None:
    """ConfigError naming the first field of `config` (a dataclass instance, and everything
    it holds) whose value is not a finite number inside its declared Range, or not one of
    its declared Choice's names. numbers_only: only whether each number of a field with a
    Range is one (number_problem), for a check of relations that must not judge a NaN by
    its size."""
    if type(config) in _FOREIGN:
        _check_foreign(config, source, where, numbers_only)
        return
    if not dataclasses.is_dataclass(config) or isinstance(config, type):
        return
    for path, value, field in _declared_fields(config, where):
        if not numbers_only:
            _check_not_empty(value, field, source, path)
            _check_length(value, field, source, path)
            _check_distinct(value, field, source, path)
        declared = range_of(field)
        if declared is not None and value is not None:
            _check_value(value, declared, source, path, numbers_only)
        _check_held(value, source, path, numbers_only)


def _declared_fields(config, where: str):
    """(path under `where`, value, dataclasses.Field) of each field of `config`."""
    for field in dataclasses.fields(config):
        path = f"{where}.{field.name}" if where else field.name
        yield path, getattr(config, field.name), field


def sized(*, length: int, items: str, default_factory):
    """A list field of `length` elements that are not numbers (those: `bounded(length=...)`);
    `items` names them in an error, e.g. "true/false values"."""
    return dataclasses.field(default_factory=default_factory,
                             metadata={_LENGTH_KEY: (length, items)})


def distinct_names(*, items: str):
    """A list field of names (empty by default) that each name once: a repeated name is a
    mistake (the same event matched twice, a field listed twice), refused naming the field
    and the name; `items` names them in the error, e.g. "corrective events"."""
    return dataclasses.field(default_factory=list, metadata={_DISTINCT_KEY: items})


def settings():
    """A list field of KEY=VALUE settings, each one as `--set` takes it (empty by default):
    its errors call the items settings and show one (grasp.grip_force=50.0), not names."""
    return dataclasses.field(default=(), metadata={_SETTINGS_KEY: True})


def holds_settings(field: dataclasses.Field) -> bool:
    """Whether `field` was declared with settings()."""
    return _SETTINGS_KEY in field.metadata


def _check_distinct(value, field: dataclasses.Field, source: str, path: str) -> None:
    if _DISTINCT_KEY not in field.metadata or not isinstance(value, (list, tuple)):
        return
    seen = set()
    for k, name in enumerate(value):
        if not isinstance(name, collections.abc.Hashable):
            continue  # a type error, which load_typed names
        if name in seen:
            from tegrasp_drake.rig.typed_yaml import ConfigError  # pydrake: on checking
            raise ConfigError(f"{source}: field '{path}' names {shown(name)} twice "
                              f"(items {value.index(name)} and {k}); list each of its "
                              f"{field.metadata[_DISTINCT_KEY]} once")
        seen.add(name)


def _check_length(value, field: dataclasses.Field, source: str, path: str) -> None:
    if _LENGTH_KEY not in field.metadata:
        return
    length, items = field.metadata[_LENGTH_KEY]
    if not isinstance(value, (list, tuple)) or len(value) != length:
        count = (f"{len(value)} elements: {shown(value)}" if isinstance(value, (list, tuple))
                 else given(value))
        from tegrasp_drake.rig.typed_yaml import ConfigError  # pydrake: loaded when checking
        raise ConfigError(f"{source}: field '{path}' must hold {length} {items}, got {count}")


def _field_default(field: dataclasses.Field):
    if field.default is not dataclasses.MISSING:
        return field.default
    if field.default_factory is not dataclasses.MISSING:
        return field.default_factory()
    return None


def _check_not_empty(value, field: dataclasses.Field, source: str, path: str) -> None:
    """An empty text or list is a value only where the field's default is itself empty (its
    documented "none", e.g. no calibration file): elsewhere it would be a silent default (an
    empty LCM URL is LCM's default bus, an empty port no device), so it is refused naming the
    field, where a config is loaded and where a public function is handed one. (A field whose
    empty value means "not set", unset_fields, is refused empty in a file by check_fields.)"""
    if not isinstance(value, (str, list, tuple)) or len(value) > 0:
        return
    default = _field_default(field)
    if not isinstance(default, (str, list, tuple)) or len(default) == 0:
        return
    from tegrasp_drake.rig.typed_yaml import ConfigError  # pydrake: loaded when checking
    raise ConfigError(f"{source}: field '{path}' is empty: give a value, or leave it out for "
                      f"its default, {shown(default)}")


def _check_value(value, declared: "Range | Choice", source: str, path: str,
                 numbers_only: bool = False) -> None:
    from tegrasp_drake.rig.typed_yaml import ConfigError  # pydrake: loaded when checking
    if isinstance(declared, Choice):
        if value not in declared.names and not numbers_only:
            raise ConfigError(f"{source}: field '{path}' {declared.words()}, got "
                              f"{given(value)}")
        return
    if declared.length is not None and not numbers_only and (
            not isinstance(value, (list, tuple)) or len(value) != declared.length):
        count = (f"{len(value)} elements: {shown(value)}" if isinstance(value, (list, tuple))
                 else given(value))
        raise ConfigError(f"{source}: field '{path}' must hold {declared.length} numbers"
                          f"{' [' + declared.unit + ']' if declared.unit else ''}, got {count}")
    for item_path, item in _values(value, path):
        item = python_scalar(item)
        if item is None:
            continue
        problem = number_problem(item)
        if problem is not None:
            raise ConfigError(f"{source}: field '{item_path}' {problem}")
        if not declared.contains(item) and not numbers_only:
            raise ConfigError(f"{source}: field '{item_path}' {declared.words(item)}, "
                              f"got {item!r}")


def _check_foreign(config, source: str, where: str, numbers_only: bool = False) -> None:
    """A Drake config object against the table declare_ranges holds for its class."""
    for name, declared in _FOREIGN[type(config)].items():
        _check_value(getattr(config, name), declared, source,
                     f"{where}.{name}" if where else name, numbers_only)


def _check_held(value, source: str, path: str, numbers_only: bool = False) -> None:
    if type(value) in _FOREIGN or (dataclasses.is_dataclass(value)
                                   and not isinstance(value, type)):
        check_ranges(value, source, path, numbers_only=numbers_only)
    elif isinstance(value, collections.abc.Mapping):
        for key, item in value.items():
            _check_held(item, source, f"{path}.{key}", numbers_only)
    elif isinstance(value, (list, tuple)):
        for k, item in enumerate(value):
            if dataclasses.is_dataclass(item) or type(item) in _FOREIGN:
                check_ranges(item, source, f"{path}[{k}]", numbers_only=numbers_only)


def _numeric(hint) -> bool:
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType, list, tuple):
        return any(_numeric(m) for m in typing.get_args(hint) if m is not Ellipsis)
    return hint in (int, float)


def _config_classes(hint) -> list:
    origin = typing.get_origin(hint)
    if origin is not None:
        return [c for m in typing.get_args(hint) if m is not Ellipsis
                for c in _config_classes(m)]
    return [hint] if dataclasses.is_dataclass(hint) or _drake_fields(hint) else []


def _drake_fields(cls) -> tuple:
    """The (name, type) of a Drake config class's fields (pydrake's `__fields__`), else ()."""
    return tuple((f.name, f.type) for f in getattr(cls, "__fields__", ()) or ()
                 if hasattr(f, "name") and hasattr(f, "type"))


def undeclared_name_lists(*roots) -> list[str]:
    """"Class.field" of every list-of-text field reachable from `roots` (dataclasses) not
    declared with distinct_names (or settings()): each such list names things, and a repeated
    name is refused only where it is declared."""
    seen, missing, pending = set(), [], list(roots)
    while pending:
        cls = pending.pop()
        if cls in seen or not dataclasses.is_dataclass(cls):
            continue
        seen.add(cls)
        hints = typing.get_type_hints(cls)
        for field in dataclasses.fields(cls):
            hint = hints[field.name]
            if (typing.get_origin(hint) in (list, tuple) and typing.get_args(hint)[:1] == (str,)
                    and _DISTINCT_KEY not in field.metadata and not holds_settings(field)):
                missing.append(f"{cls.__module__}.{cls.__qualname__}.{field.name}")
            pending.extend(_config_classes(hint))
    return sorted(missing)


def unranged_numeric_fields(*roots) -> list[str]:
    """"Class.field" of every numeric field reachable from `roots` without a Range, and of
    every Drake config field without a declare_ranges entry."""
    seen, missing, pending = set(), [], list(roots)
    while pending:
        cls = pending.pop()
        if cls in seen:
            continue
        seen.add(cls)
        if not dataclasses.is_dataclass(cls):
            missing.extend(f"{cls.__module__}.{cls.__qualname__}.{name}"
                           for name, kind in _drake_fields(cls)
                           if kind in (int, float, str) and name not in _FOREIGN.get(cls, {}))
            continue
        hints = typing.get_type_hints(cls)
        for field in dataclasses.fields(cls):
            hint = hints[field.name]
            if _numeric(hint) and range_of(field) is None:
                missing.append(f"{cls.__module__}.{cls.__qualname__}.{field.name}")
            pending.extend(_config_classes(hint))
    return sorted(missing)


def check_times_resolved(config, step_s: float, source: str, where: str = "",
                         step_name: str = "plant_config.time_step") -> None:
    """ConfigError naming the first positive time of `config` [s] shorter than the plant step
    `step_s`: it would see nothing new between steps, and a 1 ns period makes a trial crawl."""
    if not dataclasses.is_dataclass(config) or isinstance(config, type):
        return
    for path, value, field in _declared_fields(config, where):
        declared = range_of(field)
        if (isinstance(declared, Range) and declared.unit == "s" and declared.low == 0
                and declared.low_open and value is not None):
            for item_path, item in _values(value, path):
                if _is_number(item) and 0 < item < step_s:
                    from tegrasp_drake.rig.typed_yaml import ConfigError
                    raise ConfigError(
                        f"{source}: field '{item_path}' must be at least the simulation's "
                        f"time step {step_name} = {_number(step_s)} s (a time shorter than "
                        f"one step cannot be resolved), got {item!r}")
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            check_times_resolved(value, step_s, source, path, step_name)
        elif isinstance(value, (list, tuple)):
            for k, item in enumerate(value):
                check_times_resolved(item, step_s, source, f"{path}[{k}]", step_name)
