"""Which worlds run SCHED_BATCH (tools/sched_policy.py): a lockstep clock by
default, a paced one never unless asked; an unknown choice is refused."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from sim import clock_modes
from tools.sched_policy import wants_batch


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


def test_the_policy_is_taken_and_inherited():
    code = (
        "import os, subprocess, sys; from tools.sched_policy import use_batch, policy_name; "
        "assert use_batch() is None; "
        "child = subprocess.run([sys.executable, '-c', 'import os; print(os.sched_getscheduler(0))'], "
        "capture_output=True, text=True, check=True); "
        "print(policy_name(), int(child.stdout))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["SCHED_BATCH", str(os.SCHED_BATCH)]
