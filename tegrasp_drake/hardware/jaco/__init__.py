"""The JACO2 on LCM.

jaco_lcm.py: message <-> vector systems and the messages' checks.
jaco_lcm_interface.py: AddJacoLcmDriver and AddJacoLcmEmulator, the two ends of the bus."""
