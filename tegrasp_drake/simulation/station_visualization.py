"""What the simulated station shows in Meshcat: the scene, the contact forces (Drake's
ContactVisualizer), each taxel's force (TaxelForceDisplay) and a camera framed on the grasp;
all of it also into Meshcat's recording when one runs."""

import numpy as np
from pydrake.multibody.meshcat import ContactVisualizer, ContactVisualizerParams
from pydrake.visualization import ApplyVisualizationConfig, VisualizationConfig

from tegrasp_drake.simulation.taxel_force_display import TaxelForceDisplay, TaxelForceDisplayConfig

# Contact force arrows: the default 25 N grip is a 5 cm arrow (Drake's default, 10 N/m, makes
# it 2.5 m, far outside the view); moments at 1 cm per 0.01 N m.
CONTACT_NEWTONS_PER_METER = 500.0
CONTACT_NEWTON_METERS_PER_METER = 1.0
# Camera: above, in front of the fingertips and to +y, looking between the palm and the
# object, half the lift above the grasp (world) [m]: both fingers and the bars in view.
CAMERA_TARGET_FROM_OBJECT_M = (-0.03, 0.0, 0.03)
CAMERA_FROM_TARGET_M = (0.08, 0.10, 0.18)


def grasp_camera_pose(p_WO, grasp_height: float) -> tuple[np.ndarray, np.ndarray]:
    """(p_WC, p_WT): the camera position and the point it looks at [m], world frame, for
    an object at p_WO [m] grasped `grasp_height` [m] above the table."""
    x, y = p_WO[0], p_WO[1]
    target = np.array([x, y, grasp_height]) + CAMERA_TARGET_FROM_OBJECT_M
    return target + CAMERA_FROM_TARGET_M, target


def AddStationVisualization(builder, *, plant, scene_graph, taxels, pads, meshcat, camera):
    """Adds the Meshcat visualizers to the station's builder and frames the camera (`camera`:
    grasp_camera_pose's (p_WC, p_WT)); taxels: the TactilePads; pads: finger -> PadGeometry."""
    ApplyVisualizationConfig(VisualizationConfig(publish_contacts=False), builder,
                             meshcat=meshcat)
    ContactVisualizer.AddToBuilder(
        builder, plant, meshcat,
        ContactVisualizerParams(newtons_per_meter=CONTACT_NEWTONS_PER_METER,
                                newton_meters_per_meter=CONTACT_NEWTON_METERS_PER_METER))
    display = builder.AddNamedSystem("taxel_force_display", TaxelForceDisplay(
        meshcat=meshcat, pads=pads, config=TaxelForceDisplayConfig()))
    builder.Connect(plant.get_body_poses_output_port(), display.GetInputPort("body_poses"))
    for finger in pads:
        builder.Connect(taxels.GetOutputPort(f"{finger}_taxel_forces"),
                        display.GetInputPort(f"{finger}_taxel_forces"))
    meshcat.SetCameraPose(*camera)
    return display
