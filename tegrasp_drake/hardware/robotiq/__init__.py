"""The Robotiq 2F-85 on Modbus RTU (register map and units: tegrasp_drake.robotiq).

modbus_client.py: RobotiqModbusClient, activation and the command/status loop on a thread.
robotiq_driver.py: RobotiqDriver, the client as a Drake system with the gripper's ports."""
