"""Runs the CHASM benchmark (bench/chasm_bench.c) and prints its figures.

Goals (docs/chasm.md): step cost independent of the total number of states,
under 1 us per cycle for 1000 states; loading faster than 100 000 lines/s."""

import argparse
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("AUV_BUILD", ROOT / "build"))
if not BUILD.is_absolute():
    BUILD = ROOT / BUILD


def main() -> int:
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    exe = BUILD / "bin" / "chasm_bench"
    if not exe.exists():
        print(f"{exe} is not built: run `make build`", file=sys.stderr)
        return 1
    print("CHASM: load and step cost for generated plans (chains of 8, 10 tests on the active path)")
    return subprocess.run([str(exe), *sys.argv[1:]]).returncode


if __name__ == "__main__":
    sys.exit(main())
