"""`python -m tools.console`: the same as the command line front end, tools.console.cli."""

import sys

from tools.console.cli import main

sys.exit(main())
