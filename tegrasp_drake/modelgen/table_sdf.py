"""Writes models/table/table.sdf: the table (top at world z = 0, the arm's base at the
origin) with the paper's 9 object markers (Fig. 8a): EXPECTED_XY and +-1.5 cm along the
stroke (y), +-1 cm normal to the palm (x). A compliant hydroelastic top with a melamine
top's friction (materials.py)."""

from tegrasp_drake.rig import materials
from tegrasp_drake.modelgen.sdf_text import friction_text, pose_text, translation

SIZE = (1.2, 1.0, 0.05)  # m
CENTER_XY = (0.45, 0.0)  # m
EXPECTED_XY = (0.72, 0.0)  # m, the centre marker; the side grasp is reachable from 0.7 m
STROKE_OFFSETS = (-0.015, 0.0, 0.015)  # m, along world y
NORMAL_OFFSETS = (-0.010, 0.0, 0.010)  # m, along world x
MODULUS = 1.0e7  # Pa
DISSIPATION = 5.0  # s/m, Hunt-Crossley, as the pads'
RELAXATION_TIME_S = 0.02  # s, as the pads' (robotiq_sdf.PAD_RELAXATION_TIME_S)
FRICTION = materials.TABLE_TOP


def table_sdf(*, collision: bool = True) -> str:
    """The table's SDF text; without `collision`, its top and markers are visual only (the
    station then gives it another collision shape, simulation/table_model.py)."""
    top = translation((CENTER_XY[0], CENTER_XY[1], -SIZE[2] / 2))
    size = " ".join(f"{s:g}" for s in SIZE)
    markers = []
    for i, dx in enumerate(NORMAL_OFFSETS):
        for j, dy in enumerate(STROKE_OFFSETS):
            center = (EXPECTED_XY[0] + dx, EXPECTED_XY[1] + dy, 0.0002)
            color = "0.8 0.1 0.1 1" if (dx, dy) == (0.0, 0.0) else "0.1 0.3 0.8 1"
            markers.append(f'<visual name="marker_{i}{j}">{pose_text(translation(center))}'
                           "<geometry><cylinder><radius>0.003</radius><length>0.0004</length>"
                           f"</cylinder></geometry><material><diffuse>{color}</diffuse>"
                           "</material></visual>")
    collision_text = (
        f'<collision name="top">{pose_text(top)}<geometry><box><size>{size}</size></box>'
        "</geometry><drake:proximity_properties><drake:compliant_hydroelastic/>"
        f"<drake:hydroelastic_modulus>{MODULUS:g}</drake:hydroelastic_modulus>"
        f"<drake:hunt_crossley_dissipation>{DISSIPATION:g}</drake:hunt_crossley_dissipation>"
        f"<drake:relaxation_time>{RELAXATION_TIME_S:g}</drake:relaxation_time>"
        f"{friction_text(FRICTION)}</drake:proximity_properties></collision>")
    return "\n".join([
        '<?xml version="1.0"?>', '<sdf version="1.9">', '<model name="table">',
        '<link name="top">', *([collision_text] if collision else []),
        f'<visual name="top">{pose_text(top)}<geometry><box><size>{size}</size></box>'
        "</geometry><material><diffuse>0.82 0.74 0.6 1</diffuse></material></visual>",
        *markers, "</link>", "</model></sdf>"]) + "\n"
