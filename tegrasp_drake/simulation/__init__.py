"""The simulated robot, gripper, object and sensors behind the station's ports (docs/model.md).

station.py: MakeGraspStation; station_visualization.py: what it shows in Meshcat.
gripper_hands.py: the two simulated 2F-85 hands (linkage, prismatic) and what differs.
sim_robotiq_driver.py: SimRobotiqDriver, the twin of the 2F-85's own controller.
robotiq_drive_step.py, ordered_expressions.py: the drive's step compiled, in float order.
gripper_bench.py: MakeGripperBench, the simulated 2F-85 alone, for the hand's checks.
jaco_velocity_drive.py: the JACO2's velocity command path: hold, latency, servo set-point.
carriage.py, carriage_systems.py: the Cartesian carriage for sweeps, behind the arm's ports.
object_model.py, table_model.py: the object and the table added to a plant.
contact_meshing.py: ContactGeometryConfig, how finely the contact world is meshed.
body_force_pulse.py: the scenario's hit, a force pulse on the object.
validation_scenes.py: minimal scenes that check the contact world against closed form.
tactile_pads.py: TactilePads; contact_pressure.py: the exact per-taxel pressure integral.
capacitive_taxels.py: the AD7147 capacitive taxel and its calibration.
taxel_rest_noise.py: the exact distribution of the taxels' readings at rest.
taxel_force_display.py: TaxelForceDisplay, the taxel forces drawn in Meshcat.
pad_vibration_sensor.py: VibrationSensorConfig, the films' settings, sensitivity and noise.
film_dynamics.py, film_loads.py: the film's numerical core; its loads per plant step.
film_chain.py, film_readout.py: the films as one compiled Diagram; the amplifier and ADC.
pad_normal_forces.py, linkage_pad_statics.py: the pad force from contacts or joint forces.
pad_slip_vibration.py: PadSlipVibration, the pad cover's texture under slip.
drive_vibration.py: the gripper's and the arm's drive vibration as the films read it.
pad_accelerometers.py: PadAccelerometers, the paper's idealised RA transducer."""
