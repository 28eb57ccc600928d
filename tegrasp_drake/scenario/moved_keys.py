"""Scenario keys that moved when the settings were nested by concern, old dotted path -> new,
and keys a version removed (REMOVED_KEYS). User input naming an old key is refused with its
new path, or what replaced it (`refuse_moved_keys`); stored records are read through
`migrate_stored_scenario` (a moved key moved, a removed one dropped) and
`migrate_stored_overrides`.
"""

import copy

from tegrasp_drake.control.controller_config import MOVED_FIELDS as CONTROLLER_MOVED
from tegrasp_drake.control.controller_config import TAXEL_AWARE_MOVED_FIELDS
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.simulation.pad_vibration_sensor import MOVED_TO_FILM
from tegrasp_drake.simulation.sim_robotiq_driver import REMOVED_FIELDS as GRIPPER_REMOVED

# The old keys: each config class's table beside it (registered there, so that a script
# that never imports this package still gets the new path).
MOVED_KEYS = {
    **{f"controller.{old}": f"controller.{new}" for old, new in CONTROLLER_MOVED.items()},
    **{f"controller.taxel_aware.{old}": f"controller.taxel_aware.{new}"
       for old, new in TAXEL_AWARE_MOVED_FIELDS.items()},
    **{f"vibration.{name}": f"vibration.film.{name}" for name in MOVED_TO_FILM},
    "expected_object_xy": "placement.expected_xy",
    "object_offset": "placement.offset",
    "object_yaw_deg": "placement.yaw_deg",
}


# Keys a version removed, dotted path -> what replaced it (each config class's table beside
# it). A stored scenario written before (the transfer study's events under
# analysis/results_transfer*/events hold the gripper's) is read without them.
REMOVED_KEYS = {f"gripper.{name}": why for name, why in GRIPPER_REMOVED.items()}


def _moved_in(data: dict, keys=MOVED_KEYS) -> list[tuple[str, str]]:
    """(old, new) of each old key of `keys` (old -> new) that YAML data (a scenario's) holds."""
    found = []
    for old, new in keys.items():
        node = data
        parts = old.split(".")
        for part in parts[:-1]:
            node = node.get(part) if isinstance(node, dict) else None
        if isinstance(node, dict) and parts[-1] in node:
            found.append((old, new))
    return found


def refuse_moved_keys(data, source: str) -> None:
    """ConfigError naming the first old key in a scenario's YAML data and its new path."""
    if not isinstance(data, dict):
        return
    for old, new in _moved_in(data):
        raise ConfigError(f"{source}: field '{old}' is now '{new}' (the settings are nested "
                          f"by concern); write {new}")
    for old, why in _moved_in(data, REMOVED_KEYS):
        raise ConfigError(f"{source}: field '{old}' was removed: {why}; delete it")


def _move(data: dict, old: str, new: str) -> None:
    *old_parents, old_name = old.split(".")
    *new_parents, new_name = new.split(".")
    source = data
    for part in old_parents:
        source = source[part]
    value = source.pop(old_name)
    target = data
    for part in new_parents:
        target = target.setdefault(part, {})
    target[new_name] = value


def migrate_stored_scenario(data):
    """A copy of a stored record's scenario YAML data with its old keys moved to the new paths
    and its removed keys (REMOVED_KEYS) dropped."""
    if not isinstance(data, dict):
        return data
    data = copy.deepcopy(data)
    for old, new in _moved_in(data):
        _move(data, old, new)
    for old, _ in _moved_in(data, REMOVED_KEYS):
        *parents, name = old.split(".")
        node = data
        for part in parents:
            node = node[part]
        del node[name]
    return data


def migrate_stored_overrides(assignments) -> list[str]:
    """Stored-record migration: a sweep record's scenario_overrides (`key=value`) written before
    the move, each old key replaced by its new path. Only for reading stored records."""
    migrated = []
    for assignment in assignments:
        key, equals, value = str(assignment).partition("=")
        migrated.append(MOVED_KEYS.get(key.strip(), key) + equals + value if equals
                        else assignment)
    return migrated


def migrate_stored_trial(trial: dict) -> dict:
    """Stored-record migration: a sweep record's trial spec with its scenario_overrides
    migrated (migrate_stored_overrides); the trial itself when it has none to migrate."""
    overrides = trial.get("scenario_overrides")
    if not overrides:
        return trial
    return {**trial, "scenario_overrides": migrate_stored_overrides(overrides)}
