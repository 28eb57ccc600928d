"""Reading a sweep spec from a YAML file: `LoadSweepSpec`, with the same parser and field
checks as every configuration file (rig/typed_yaml.py); the spec's frozen dataclasses are
built from the checked data, since Drake's `yaml_load_typed` cannot build them."""

from collections.abc import Collection
from dataclasses import dataclass

from tegrasp_drake.rig.typed_yaml import (ConfigError, RefinedSettings, check_fields,
                                          read_yaml_file, refuse_null_section, require_fields,
                                          require_mapping)
from tegrasp_drake.sweep.spec import (BUILTIN_OBJECTS, CONTROLLER_NAMES, RENAMED_OBJECT_FIELDS,
                                      SPEC_COUNTS, USER_OBJECT_FIELDS, RandomisationConfig,
                                      SweepSpec, check_spec_counts, is_number, product_grid,
                                      user_object, validate_spec)
from tegrasp_drake.rig.api_boundary import PathLike, public_api


@dataclass
class _ProductGrid:
    """The mapping form of a spec's `grid`: the product of two offset lists [m]."""
    normal_offsets_m: list[float]
    stroke_offsets_m: list[float]


@public_api
def LoadSweepSpec(path: PathLike, *, builtin_objects: Collection[str] = BUILTIN_OBJECTS,
                    controllers: Collection[str] = CONTROLLER_NAMES) -> SweepSpec:
    """Reads and validates a YAML sweep spec (analysis/example_sweep.yaml shows each field);
    fields left out keep the paper's defaults. `grid` is a list of [dx_m, dy_m] or the product
    of normal_offsets_m and stroke_offsets_m. ConfigError names the file and the field."""
    fields = read_yaml_file(path, "the sweep spec", kind=SweepSpec)
    # Not a request for the paper's 243-trial experiment (which running without --spec gives).
    require_fields(fields, path, "the sweep spec", "give at least one field (e.g. objects: "
                   "[box]), or leave out --spec for the paper's experiment")
    require_mapping(fields, path, "the sweep spec", "fields (objects, controllers, grid, "
                    "attempts, ...)")
    return sweep_spec_from_fields(fields, str(path),
                                  builtin_objects=builtin_objects, controllers=controllers)


def sweep_spec_from_fields(fields, source: str, *,
                           builtin_objects: Collection[str] = BUILTIN_OBJECTS,
                           controllers: Collection[str] = CONTROLLER_NAMES,
                           written: bool = True) -> SweepSpec:
    """The SweepSpec of a spec file's parsed YAML data (LoadSweepSpec), or of a section of
    another file holding the same fields (a transfer spec's `sweep`); errors name `source`.
    written: the fields are the user's as written, whose scenario_overrides may not set one
    key twice (False for overrides the package composed, a world's preset before them)."""
    def fail(field_name, message):
        raise ConfigError(f"{source}: field '{field_name}': {message}")

    if isinstance(fields, dict):  # cheap checks first: nothing is built from a long list
        check_spec_counts(_written_counts(fields), source)
    # The grid has two forms, a list of markers or a product grid: it is read on its own.
    has_grid = isinstance(fields, dict) and "grid" in fields
    grid = fields.pop("grid") if has_grid else None
    if isinstance(fields, dict):
        _check_user_object_fields(fields.get("user_objects"), fail)
    check_fields(fields, SweepSpec, source)
    if has_grid:
        fields["grid"] = _parse_grid(grid, source, fail)
    for name in ("objects", "controllers", "scenario_overrides"):
        if name in fields:
            fields[name] = tuple(fields[name])
    if not written and "scenario_overrides" in fields:  # validate_spec checks the written
        fields["scenario_overrides"] = RefinedSettings(fields["scenario_overrides"])
    if "randomisation" in fields:
        fields["randomisation"] = RandomisationConfig(**fields["randomisation"])
    if "user_objects" in fields:
        fields["user_objects"] = {str(name): user_object(str(name), definition)
                                  for name, definition in fields["user_objects"].items()}

    spec = SweepSpec(**fields)
    validate_spec(spec, source, builtin_objects=builtin_objects, controllers=controllers)
    return spec


def _written_counts(fields: dict) -> dict[str, tuple[int, str]]:
    """check_spec_counts's counts of a spec's lists as written: a product grid's markers
    by its two lists' lengths, before the product is built."""
    counts = {name: (len(fields[name]), "") for name in SPEC_COUNTS
              if isinstance(fields.get(name), (list, dict))}
    grid = fields.get("grid")
    if isinstance(grid, dict):
        normal, stroke = grid.get("normal_offsets_m"), grid.get("stroke_offsets_m")
        if isinstance(normal, list) and isinstance(stroke, list):
            counts["grid"] = (len(normal) * len(stroke), f"{len(normal)} normal_offsets_m x "
                              f"{len(stroke)} stroke_offsets_m")
        else:
            del counts["grid"]  # its fields' types: check_fields names them
    return counts


def _offsets(values, field_name, fail) -> tuple[float, ...]:
    if not values:
        fail(field_name, "is empty: a sweep needs at least one marker offset")
    return tuple(float(v) for v in values)


def _parse_grid(value, source, fail) -> tuple[tuple[float, float], ...]:
    refuse_null_section(value, source, "grid")
    if isinstance(value, dict):
        check_fields(value, _ProductGrid, source, "grid")
        return product_grid(_offsets(value["normal_offsets_m"], "grid.normal_offsets_m", fail),
                            _offsets(value["stroke_offsets_m"], "grid.stroke_offsets_m", fail))
    if isinstance(value, list):
        grid = []
        for item in value:
            if (not isinstance(item, list) or len(item) != 2
                    or not all(is_number(v) for v in item)):
                fail("grid", f"marker offset {item!r} is not a pair [dx_m, dy_m] of numbers")
            grid.append((float(item[0]), float(item[1])))
        return tuple(grid)  # validate_spec rejects an empty list.
    fail("grid", "expected a list of [dx_m, dy_m] offsets or a mapping with "
                 f"normal_offsets_m and stroke_offsets_m, got {value!r}")


def _check_user_object_fields(user_objects, fail):
    """User objects' fields are USER_OBJECT_FIELDS; an old name is refused with its new one."""
    if not isinstance(user_objects, dict):
        return  # check_fields names the type
    for name, fields in user_objects.items():
        for key in fields if isinstance(fields, dict) else ():
            if key in RENAMED_OBJECT_FIELDS:
                fail(f"user_objects.{name}.{key}", "is the old name of the field: rename "
                     + ", ".join(f"{old} to {new}" for old, new in
                                 RENAMED_OBJECT_FIELDS.items()))
            if key not in USER_OBJECT_FIELDS:
                fail(f"user_objects.{name}.{key}", "unknown field (known: "
                     f"{', '.join(USER_OBJECT_FIELDS)})")
