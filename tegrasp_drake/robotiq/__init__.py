"""The Robotiq 2F-85 gripper: what every side of the project knows about it.

Here, shared by the simulation, the hardware driver, the emulator and the model generators
(plain Python and numpy, no Drake systems):

- `units`: the `gripper.command` [rPR, rSP, rFR] and `gripper.status` [gACT, gGTO, gSTA,
  gOBJ, gFLT, gPR, gPO, gCU] byte vectors, their conversions to SI units (stroke, speed,
  force, motor current) and the manual's fault codes;
- `registers`: the Modbus RTU register map (serial settings, addresses, function codes)
  and the pure encode/decode between registers and those vectors;
- `linkage`: the finger's underactuated five-bar in closed form, the one source of its
  dimensions (pad travel, opening for a driver angle, the flip height);
- `drive`: the motor, the firmware's position loop, the current limit and the
  self-locking screw behind the linkage, their parameters and a lumped model of the grip
  force's rise (`grip_rise`);
- `dimensions`: the hand's dimensions the models and the arm's grasp frame share.

Each side keeps its own module in its own layer, importing from here:

- model: `modelgen/robotiq_sdf.py` (the prismatic hand) and
  `modelgen/robotiq_linkage_sdf.py` (the five-bar hand) write models/robotiq_2f85/;
- simulation: `simulation/sim_robotiq_driver.py` (SimRobotiqDriver, the simulated
  controller behind `gripper.command` / `gripper.status`) and `simulation/gripper_hands.py`
  (the two simulated hands, five-bar and prismatic: each one's actuated joint and how it
  maps to the pad opening);
- hardware: `hardware/robotiq/modbus_client.py` (RobotiqModbusClient, the serial thread)
  and `hardware/robotiq/robotiq_driver.py` (RobotiqDriver, the system with the same ports
  as the simulated twin);
- emulator: `emulators/robotiq_emulator.py` (RobotiqEmulator, the gripper on a
  pseudo-terminal, answering the real register map).
"""
