"""The Robotiq 2F-85: what the simulation, the hardware driver, the emulator and the model
generators all know about it (plain Python and numpy, no Drake systems).

units.py: the command and status byte vectors, their SI conversions and fault codes.
registers.py: the Modbus RTU register map and the encoding of those vectors.
linkage.py: the finger's five-bar in closed form, the one source of its dimensions.
drive.py: the rotor, position loop, current limit and screw, and `grip_rise`.
dimensions.py: the hand's dimensions the models and the arm's grasp frame share.
hand_models.py: the simulated hand models' names (`gripper.model`)."""
