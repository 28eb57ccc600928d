"""What the software costs, run from a checkout (not installed with the package):
`python -m benchmarks.trial` (a trial per controller against the plant alone),
`python -m benchmarks.matcher` (one tick of the event matcher), `python -m
benchmarks.drivers` and `python -m benchmarks.hardware_loop` (the real-time loop against
the emulated devices). Each prints its figures; none is a pass/fail test."""
