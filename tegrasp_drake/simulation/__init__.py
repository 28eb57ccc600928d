"""The simulated robot, gripper, object and sensors behind the station's ports (docs/model.md).

station.py: MakeGraspStation, the simulated station as one Diagram.
station_visualization.py: what the station shows in Meshcat.
gripper_hands.py: the two simulated 2F-85 hands (linkage, prismatic) and what differs.
sim_robotiq_driver.py: SimRobotiqDriver, the twin of the 2F-85's own controller.
gripper_bench.py: MakeGripperBench, the simulated 2F-85 alone, for the hand's checks.
jaco_velocity_drive.py: the JACO2's velocity command path: hold, latency, servo set-point.
carriage.py: the Cartesian carriage that stands in for the arm in sweeps.
carriage_systems.py: CarriageCommand and CarriageWristWrench, the carriage behind the arm ports.
object_model.py: the scenario's object added to a plant.
table_model.py: the table added to a plant, as a box or a half-space.
contact_meshing.py: ContactGeometryConfig, how finely the contact world is meshed.
body_force_pulse.py: the scenario's hit, a force pulse on the object.
validation_scenes.py: minimal scenes that check the contact world against closed form.
tactile_pads.py: TactilePads, the taxel forces from the hydroelastic contact surfaces.
contact_pressure.py: the exact per-taxel integral of a contact surface's pressure.
capacitive_taxels.py: the AD7147 capacitive taxel and its calibration.
taxel_rest_noise.py: the exact distribution of the taxels' readings at rest.
taxel_force_display.py: TaxelForceDisplay, the taxel forces drawn in Meshcat.
pad_vibration_sensor.py: VibrationSensorConfig, the films' settings, sensitivity and noise.
film_dynamics.py: the film's numerical core, pure numpy.
film_loads.py: FilmLoads, each film's loads per plant step from the plant's contacts.
film_chain.py: the films as one Diagram of compiled systems.
film_readout.py: the charge amplifier's swing and the myRIO's converter.
pad_normal_forces.py: PadNormalForces, each finger's contact force along its pad normal.
linkage_pad_statics.py: the same force from the joints' generalized contact forces.
pad_slip_vibration.py: PadSlipVibration, the pad cover's texture under slip.
drive_vibration.py: the gripper's and the arm's drive vibration as the films read it.
pad_accelerometers.py: PadAccelerometers, the paper's idealised RA transducer.
"""
