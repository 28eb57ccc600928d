"""`python -m tegrasp_drake ...`: the tegrasp command line (cli.py)."""

import sys

from tegrasp_drake.cli import main

sys.exit(main())
