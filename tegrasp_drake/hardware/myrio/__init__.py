"""The myRIO tactile stream on a serial port (frame: TACTILE_FRAME.md).

tactile_frame.py: the binary frame, its encoder and the streaming decoder.
serial_reader.py: TactileSerialReader, the reader thread with a bounded queue.
device_clock.py: the device's clock against the frames' arrival (a stream too fast to be true).
tactile_calibration.py: counts to newtons, piezo samples to m/s^2, zeroing sums.
tactile_serial_receiver.py: TactileSerialReceiver, the pads as a Drake system."""
