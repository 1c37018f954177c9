"""`python -m tools.report`: the same as the command line front end, tools.report.cli."""

import sys

from tools.report.cli import main

sys.exit(main())
