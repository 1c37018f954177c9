"""Print make variables locating what the pinned wheels carry.

The lcm wheel has no pkg-config file: its headers, library, tools and jars sit
beside the Python package in site-packages. cmeel-eigen installs Eigen under
site-packages/cmeel.prefix. The Makefile includes this output as build/config.mk.
"""

import os
import sys

import lcm


def main() -> int:
    site = os.path.realpath(os.path.join(os.path.dirname(lcm.__file__), ".."))
    paths = {
        "LCM_PREFIX": site,
        "LCM_INC": os.path.join(site, "include"),
        "LCM_LIB": os.path.join(site, "lib"),
        "LCM_BIN": os.path.realpath(lcm.LCM_BIN_DIR),
        "EIGEN_INC": os.path.join(site, "cmeel.prefix", "include", "eigen3"),
    }
    for name, path in paths.items():
        if not os.path.isdir(path):
            print(f"wheel_paths: {name} folder {path} is missing", file=sys.stderr)
            return 1
        print(f"{name} := {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
