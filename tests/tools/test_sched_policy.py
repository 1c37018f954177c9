"""Which worlds run SCHED_BATCH (tools/launch/sched_policy.py): a lockstep clock by
default, a paced one never unless asked; an unknown choice is refused."""

from __future__ import annotations

import os
import sys
import time

import pytest

from sim import clock_modes
from tools.launch import procs
from tools.launch.sched_policy import wants_batch


@pytest.mark.parametrize(
    "mode, choice, batch",
    [
        (clock_modes.LOCKSTEP, "auto", True),
        (clock_modes.REALTIME, "auto", False),
        (clock_modes.SCALED, "auto", False),
        (clock_modes.REALTIME, "batch", True),
        (clock_modes.LOCKSTEP, "normal", False),
    ],
)
def test_the_choice(mode, choice, batch):
    assert wants_batch(mode, choice) is batch


def test_an_unknown_choice_is_refused():
    with pytest.raises(ValueError, match="--sched fastest"):
        wants_batch(clock_modes.LOCKSTEP, "fastest")


def test_the_launchers_children_take_it_and_the_launcher_does_not(tmp_path):
    probe = [sys.executable, "-c", "import os, time; print(os.sched_getscheduler(0), flush=True); time.sleep(600)"]
    try:
        for on, want in ((True, os.SCHED_BATCH), (False, os.SCHED_OTHER)):
            procs.children_batch(on)
            child = procs.Child("probe", probe, tmp_path / f"probe{on}.out").start()
            try:
                deadline = time.monotonic() + 20
                while not child.out.read_text().strip() and time.monotonic() < deadline:
                    time.sleep(0.05)
                assert int(child.out.read_text()) == want
                assert os.sched_getscheduler(child.pid) == want
            finally:
                child.stop()
            assert os.sched_getscheduler(0) == os.SCHED_OTHER  # the starting process keeps its own
    finally:
        procs.children_batch(False)
