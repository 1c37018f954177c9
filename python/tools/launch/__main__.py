"""`python -m tools.launch`: the same as the command line front end, tools.launch.cli."""

import sys

from tools.launch.cli import main

sys.exit(main())
