"""MakeGripperBench: the simulated 2F-85 alone, its base frame the world frame (z the
approach axis, y the stroke; no gravity on it), playing one command, for the hand's checks
against closed form. Optionally an obstacle between the fingers and a constant outward push
on the left pad's centre."""

import dataclasses

import numpy as np
from pydrake.geometry import Box, Cylinder, ProximityProperties
from pydrake.geometry import (AddCompliantHydroelasticProperties, AddContactMaterial,
                              AddRigidHydroelasticProperties)
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.plant import AddMultibodyPlant, CoulombFriction, MultibodyPlantConfig
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource

from tegrasp_drake.modelgen.robotiq_sdf import PAD_DISSIPATION
from tegrasp_drake.robotiq import linkage
from tegrasp_drake.rig import paths
from tegrasp_drake.simulation.body_force_pulse import BodyForcePulse
from tegrasp_drake.simulation.gripper_hands import (actuated_state_selector, add_gripper_model,
                                                    configure_drive, gripper_hand)
from tegrasp_drake.simulation.pad_normal_forces import PadNormalForces
from tegrasp_drake.simulation.sim_robotiq_driver import (GripperDriverConfig,
                                                         MakeSimRobotiqDriver)
from tegrasp_drake.simulation.station import pad_geometries


@dataclasses.dataclass
class BenchObstacle:
    """An obstacle welded at (0, 0, z_m) [m] in the base frame: `box` (size x y z [m]) or
    `rod` along x (size [diameter, length]); rigid, or compliant of hydroelastic_modulus
    [Pa] with the pads' dissipation."""
    shape: str
    size: tuple
    z_m: float
    friction: float = 0.5
    hydroelastic_modulus: float | None = None
    resolution_hint_m: float = 0.002


@dataclasses.dataclass
class GripperBench:
    """A built bench: the diagram and its parts."""
    diagram: object
    plant: object
    gripper: object
    pad_forces: object


def _add_obstacle(plant, obstacle: BenchObstacle) -> None:
    properties = ProximityProperties()
    if obstacle.hydroelastic_modulus is None:
        AddRigidHydroelasticProperties(resolution_hint=obstacle.resolution_hint_m,
                                       properties=properties)
        dissipation = None
    else:
        AddCompliantHydroelasticProperties(resolution_hint=obstacle.resolution_hint_m,
                                           hydroelastic_modulus=obstacle.hydroelastic_modulus,
                                           properties=properties)
        dissipation = PAD_DISSIPATION  # so that the pair's is the pads' whatever the moduli
    AddContactMaterial(dissipation=dissipation,
                       friction=CoulombFriction(obstacle.friction, obstacle.friction),
                       properties=properties)
    if obstacle.shape == "box":
        shape, X = Box(*obstacle.size), RigidTransform([0.0, 0.0, obstacle.z_m])
    elif obstacle.shape == "rod":
        shape = Cylinder(obstacle.size[0] / 2, obstacle.size[1])
        X = RigidTransform(RollPitchYaw(0.0, np.pi / 2, 0.0), [0.0, 0.0, obstacle.z_m])
    else:
        raise ValueError(f"obstacle shape '{obstacle.shape}' is not box or rod")
    plant.RegisterCollisionGeometry(plant.world_body(), X, shape, "obstacle", properties)


def MakeGripperBench(*, command, driver: GripperDriverConfig = GripperDriverConfig(),
                     obstacle: BenchObstacle | None = None, push_n: float = 0.0,
                     push_start_s: float = 0.0,
                     plant_config: MultibodyPlantConfig | None = None,
                     pad_refinement: int = 0) -> GripperBench:
    """The gripper of `driver.model` playing `command` (rPR, rSP, rFR) from open."""
    plant_config = plant_config or MultibodyPlantConfig(
        time_step=1e-3, discrete_contact_approximation="lagged",
        contact_model="hydroelastic_with_fallback")
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(plant_config, builder)
    hand = gripper_hand(driver.model)
    gripper = add_gripper_model(paths.make_parser(plant), hand, pad_refinement)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", gripper))
    if obstacle is not None:
        _add_obstacle(plant, obstacle)
    plant.set_gravity_enabled(gripper, False)
    configure_drive(plant, gripper, hand, driver)
    plant.Finalize()
    plant.SetDefaultPositions(gripper, hand.default_positions())

    sim_driver = builder.AddNamedSystem("gripper_driver", MakeSimRobotiqDriver(
        config=driver, time_step=plant.time_step()))
    selector = builder.AddSystem(actuated_state_selector(plant, gripper, hand))
    builder.Connect(plant.get_state_output_port(gripper), selector.get_input_port())
    builder.Connect(selector.get_output_port(), sim_driver.GetInputPort("finger_state"))
    builder.Connect(sim_driver.GetOutputPort("desired_state"),
                    plant.get_desired_state_input_port(gripper))
    source = builder.AddSystem(ConstantVectorSource(np.asarray(command, float)))
    builder.Connect(source.get_output_port(), sim_driver.GetInputPort("command"))

    pads = pad_geometries(plant, scene_graph, gripper)
    pad_forces = builder.AddNamedSystem("pad_normal_forces",
                                        PadNormalForces(plant=plant, pads=pads))
    builder.Connect(plant.get_contact_results_output_port(),
                    pad_forces.GetInputPort("contact_results"))
    builder.Connect(plant.get_body_poses_output_port(), pad_forces.GetInputPort("body_poses"))
    if push_n:
        left = pads["left"]
        # +y: the left pad's outward normal on the pin
        push = builder.AddSystem(BodyForcePulse(body_index=left.body_index,
                                                p_BQ=left.X_BP.translation(),
                                                f_W=[0.0, push_n, 0.0], start_s=push_start_s))
        builder.Connect(push.get_output_port(), plant.get_applied_spatial_force_input_port())
    diagram = builder.Build()
    diagram.set_name("gripper_bench")
    return GripperBench(diagram, plant, gripper, pad_forces)


def loop_closure_error_m(plant, plant_context, gripper) -> float:
    """The largest gap [m] between the follower's and spring link's copies of joint D."""
    worst = 0.0
    for finger, sign in (("left", 1.0), ("right", -1.0)):
        p_D = np.array([0.0, sign * linkage.D[0], linkage.D[1]])
        follower = plant.GetBodyByName(f"{finger}_finger", gripper)
        spring_link = plant.GetBodyByName(f"{finger}_spring_link", gripper)
        gap = (plant.EvalBodyPoseInWorld(plant_context, follower).multiply(p_D)
               - plant.EvalBodyPoseInWorld(plant_context, spring_link).multiply(p_D))
        worst = max(worst, float(np.linalg.norm(gap)))
    return worst
