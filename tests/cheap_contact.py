"""The cheap contact: Drake's own pad mesh and one contact-surface face a polygon (no tests here).

The default contact cuts each hydroelastic polygon into triangles and meshes the linkage pads
finer (tegrasp_drake/simulation/contact_meshing.py): more SAP constraints, against the friction
creep of a held object, at 3-13 times a trial's CPU. A test whose claim does not depend on how a
held grip creeps (file handling, command plumbing, resumption, recording logic) pins this
cheaper contact instead, with one line saying why, in every world it runs and records events in.
"""

import json

# `--set` assignments (KEY=VALUE) of the cheap contact.
CHEAP_CONTACT = ("contact_geometry.pad_refinement=0",
                 "plant_config.contact_surface_representation=polygon")


def cheap_contact_arguments() -> list[str]:
    """The cheap contact as command-line options: `--set KEY=VALUE` for each assignment."""
    return [word for assignment in CHEAP_CONTACT for word in ("--set", assignment)]


def cheap_contact_yaml() -> str:
    """The cheap contact as a YAML flow list of assignments (a sweep's `scenario_overrides`
    or a transfer world's `overrides`)."""
    return json.dumps(list(CHEAP_CONTACT))  # JSON is YAML


CHEAP_CONTACT_SECTIONS = {"contact_geometry": {"pad_refinement": 0},
                          "plant_config": {"contact_surface_representation": "polygon"}}
"""The cheap contact as the sections of a scenario file's preset."""
