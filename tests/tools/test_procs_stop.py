"""tools.launch.procs.stop_together: a tier at a time, the highest first, and the
children of one tier together (the launcher's stop at the end of every run)."""

from __future__ import annotations

import sys
from pathlib import Path

from tools.launch.procs import Child, stop_together

# A child that, on SIGINT, marks that it was asked, then exits 0 only when
# every name in WAIT_ASKED was asked too (a one-by-one stop would leave them
# unasked: it would be killed after the timeout) and every name in
# WAIT_GONE has already exited (the tier above went first); else exits 3.
CHILD = r"""
import os, signal, sys, time
from pathlib import Path
d, me = Path(sys.argv[1]), sys.argv[2]
asked_of = [n for n in sys.argv[3].split(",") if n]
gone_of = [n for n in sys.argv[4].split(",") if n]
def on_int(*_):
    (d / f"{me}.asked").touch()
    if not all((d / f"{n}.gone").exists() for n in gone_of):
        sys.exit(3)
    end = time.monotonic() + 20
    while time.monotonic() < end:
        if all((d / f"{n}.asked").exists() for n in asked_of):
            (d / f"{me}.gone").touch()
            sys.exit(0)
        time.sleep(0.01)
    sys.exit(4)
signal.signal(signal.SIGINT, on_int)
(d / f"{me}.ready").touch()
while True:
    time.sleep(1)
"""


def _child(tmp: Path, name: str, tier: int, asked: list[str], gone: list[str]) -> Child:
    cmd = [sys.executable, "-c", CHILD, str(tmp), name, ",".join(asked), ",".join(gone)]
    return Child(name, cmd, tmp / f"{name}.out", tier=tier)


def _wait_ready(tmp: Path, names: list[str]) -> None:
    import time

    end = time.monotonic() + 30
    while not all((tmp / f"{n}.ready").exists() for n in names):
        assert time.monotonic() < end, "children did not start"
        time.sleep(0.02)


def test_a_tier_stops_together_and_the_higher_tier_first(tmp_path: Path) -> None:
    managers = ["m1", "m2", "m3"]
    sims = ["s1", "s2"]
    children = [_child(tmp_path, n, 0, sims, managers) for n in sims]
    children += [_child(tmp_path, n, 2, managers, []) for n in managers]
    for c in children:
        c.start()
    _wait_ready(tmp_path, sims + managers)
    # 10 s: a child of a tier stopped one by one would wait 20 s for its siblings
    codes = stop_together(children, timeout=10.0)
    assert codes == {n: 0 for n in sims + managers}, [c.tail() for c in children]
    assert all(c.stopping for c in children)


def test_a_child_that_ignores_the_stop_is_killed_at_the_deadline(tmp_path: Path) -> None:
    stubborn = Child(
        "stubborn",
        [
            sys.executable,
            "-c",
            "import signal, sys, time; from pathlib import Path; signal.signal(signal.SIGINT, signal.SIG_IGN); "
            "Path(sys.argv[1]).touch(); time.sleep(60)",
            str(tmp_path / "stubborn.ready"),
        ],
        tmp_path / "stubborn.out",
    )
    gone = Child("gone", [sys.executable, "-c", "pass"], tmp_path / "gone.out")
    stubborn.start()
    gone.start()
    gone.proc.wait()
    _wait_ready(tmp_path, ["stubborn"])  # it ignores SIGINT from here on
    codes = stop_together([stubborn, gone], timeout=1.0)
    assert codes == {"stubborn": -9, "gone": 0}
