"""Mission commands and plugin uploads as the managers take them (one place for
the console and the operator command line).

A command goes to <VEHICLE>.MISSION_CMD, an upload to <VEHICLE>.PLUGIN_UPLOAD;
every manager addressed answers on <VEHICLE>.MISSION_ACK with the same seq.
"""

from __future__ import annotations

import hashlib
import os
import random
import time
from pathlib import Path

from auv import mission_command_t, plugin_upload_t

COMMANDS = {
    "start": mission_command_t.CMD_START,
    "pause": mission_command_t.CMD_PAUSE,
    "resume": mission_command_t.CMD_RESUME,
    "abort": mission_command_t.CMD_ABORT,
    "load": mission_command_t.CMD_LOAD_PLAN,
    "stop": mission_command_t.CMD_STOP,
}
RESULTS = ("ok", "rejected", "failed")
# The managers' documented maximum (MGR_MAX_PLAN_BYTES, docs/channels.md): a larger
# plan may be lost in the kernel without an answer, so it is refused before sending.
MAX_PLAN_BYTES = 256 * 1024


def first_seq() -> int:
    """A starting seq unlikely to meet another operator's (acks are matched by seq)."""
    return random.SystemRandom().randrange(1, 1 << 30)


def who() -> str:
    return f"{os.environ.get('USER', 'operator')}@{os.uname().nodename}"


def command(
    vehicle: str,
    manager: str,
    name: str,
    seq: int,
    utime: int = 0,
    plan_name: str = "",
    plan_text: str = "",
    reason: str = "",
) -> mission_command_t:
    if name not in COMMANDS:
        raise ValueError(f"unknown command {name!r}: one of {', '.join(COMMANDS)}")
    if name == "load" and not plan_text:
        raise ValueError("load needs a plan's text")
    if len(plan_text.encode()) > MAX_PLAN_BYTES:
        raise ValueError(f"the plan is {len(plan_text.encode())} bytes, the managers take at most {MAX_PLAN_BYTES}")
    msg = mission_command_t()
    msg.utime = utime or int(time.time() * 1e6)
    msg.vehicle, msg.manager, msg.seq, msg.command = vehicle, manager, seq, COMMANDS[name]
    msg.plan_name, msg.plan_text, msg.reason = plan_name, plan_text, reason or who()
    return msg


def upload(
    vehicle: str, manager: str, path: Path, seq: int, version: str = "1", name: str = "", utime: int = 0
) -> plugin_upload_t:
    data = path.read_bytes()
    msg = plugin_upload_t()
    msg.utime = utime or int(time.time() * 1e6)
    msg.vehicle, msg.manager, msg.seq = vehicle, manager, seq
    msg.plugin_name = name or _plugin_name(path)
    msg.plugin_version = version
    msg.sha256_hex = hashlib.sha256(data).hexdigest()
    msg.n_bytes, msg.data = len(data), data
    return msg


def _plugin_name(path: Path) -> str:
    """chasm_survey.so (the managers' own file naming) or survey.so -> survey."""
    stem = path.name.split(".so")[0]
    return stem[len("chasm_") :] if stem.startswith("chasm_") else stem
