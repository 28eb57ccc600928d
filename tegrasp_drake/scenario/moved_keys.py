"""Scenario keys that moved when the settings were nested by concern, old dotted path -> new.
User input naming an old key is refused with its new path (`refuse_moved_keys`); stored
records are read through `migrate_stored_scenario` and `migrate_stored_overrides`.
"""

import copy

from tegrasp_drake.rig.typed_yaml import ConfigError

# The controller's settings, by section (control/controller_config.py).
_CONTROLLER = {
    "re_reach_enabled": "re_reach.enabled",
    "one_sided_contact_s": "re_reach.one_sided_contact_s",
    "reach_event_timeout_s": "re_reach.reach_event_timeout_s",
    "max_re_reaches": "re_reach.max_re_reaches",
    "re_reach_move_s": "re_reach.move_s",
    "opened_m": "re_reach.opened_m",
    "lift_load_enabled": "lift_load.enabled",
    "slip_vibration_mps2": "lift_load.slip_vibration_mps2",
    "slip_vibration_sigmas": "lift_load.slip_vibration_sigmas",
    "slip_band_hz": "lift_load.slip_band_hz",
    "slip_window_s": "lift_load.slip_window_s",
    "slip_s": "lift_load.slip_s",
    "lift_load_force_factor": "lift_load.force_factor",
    "max_lift_loads": "lift_load.max_lift_loads",
    "max_grip_force_n": "lift_load.max_grip_force_n",
    "grip_fraction": "lift_load.grip_fraction",
    "relift_settle_s": "lift_load.relift_settle_s",
    "avoid_enabled": "avoid.enabled",
    "hit_ra_mps2": "avoid.hit_ra_mps2",
    "hit_ra_sigmas": "avoid.hit_ra_sigmas",
    "hit_refractory_s": "avoid.hit_refractory_s",
    "avoid_sense_s": "avoid.sense_s",
    "avoid_sa_asymmetry_n": "avoid.sa_asymmetry_n",
    "avoid_distance_m": "avoid.distance_m",
    "avoid_s": "avoid.move_s",
    "place_event_timeout_s": "place.event_timeout_s",
    "memorized_corrective_events": "memorized_corrective.events",
    "lift_load_event_thresholds": "memorized_corrective.lift_load_thresholds",
    "hold_avoid_event_thresholds": "memorized_corrective.hold_avoid_thresholds",
    "memorized_hit_baseline_s": "memorized_corrective.hit_baseline_s",
    "memorized_hit_armed_s": "memorized_corrective.hit_armed_s",
    "sa_threshold": "matching.sa_threshold",
    "ra_threshold": "matching.ra_threshold",
    "ra_envelope_hz": "matching.ra_envelope_hz",
    "ra_noise_floor_sigmas": "matching.ra_noise_floor_sigmas",
    "ra_noise_quiet_s": "matching.ra_noise_quiet_s",
    "flat_template_needs_flat_window": "matching.flat_template_needs_flat_window",
}
# The film's mechanics (simulation/pad_vibration_sensor.py).
_FILM = ("mode_frequency_hz", "mode_damping_ratio", "mode_mass_kg", "load_lowpass_hz",
         "impact_enabled", "pad_contact_stiffness_n_per_m", "pad_dissipation_s_per_m",
         "film_charge_gain_c_per_m", "feedback_capacitance_f")

MOVED_KEYS = {
    **{f"controller.{old}": f"controller.{new}" for old, new in _CONTROLLER.items()},
    **{f"vibration.{name}": f"vibration.film.{name}" for name in _FILM},
    "expected_object_xy": "placement.expected_xy",
    "object_offset": "placement.offset",
    "object_yaw_deg": "placement.yaw_deg",
}


def _moved_in(data: dict) -> list[tuple[str, str]]:
    """(old, new) of each old key that YAML data (a scenario's) holds."""
    found = []
    for old, new in MOVED_KEYS.items():
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
    """A copy of a stored record's scenario YAML data with its old keys moved to the new paths."""
    if not isinstance(data, dict):
        return data
    data = copy.deepcopy(data)
    for old, new in _moved_in(data):
        _move(data, old, new)
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


def _register_moved_attributes() -> None:
    """Script assignments of a moved setting (`config.re_reach_enabled = False`) are refused
    naming the new path (api_boundary.public_dataclass)."""
    from tegrasp_drake.control.controller_config import GraspControllerConfig
    from tegrasp_drake.rig.api_boundary import register_moved_fields
    from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
    register_moved_fields(GraspControllerConfig, _CONTROLLER)
    register_moved_fields(VibrationSensorConfig, {name: f"film.{name}" for name in _FILM})


_register_moved_attributes()
