"""`python -m tools.montecarlo`: the same as the command line front end, tools.montecarlo.cli."""

import sys

from tools.montecarlo.cli import main

sys.exit(main())
