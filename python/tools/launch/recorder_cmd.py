"""The run's recorder: its command line and whether it takes part in the clock.

One definition for every host that may record: the launcher (`auv-launch`, its
own log) and a host agent (`tools/hosts/agent_part.py`, when the scenario logs on its
host). Both start the recorder the scenario names (`logging.recorder`):
auv-recorder (c/recorder: loses nothing it receives, counts what the kernel
dropped, and in a lockstep world is the participant SIM.RECORDER, so time
waits for it) or lcm-logger (its subscription queue holds 30 messages and
drops messages of a busy fast-time run).
"""

from __future__ import annotations

from pathlib import Path

import lcm

from auvlcm import programs


def recorder_cmd(recorder: str, url: str, log_path: Path, stats_path: Path, build: Path) -> list[str]:
    """The command that records url into log_path (auv-recorder also writes its
    counts to stats_path at exit)."""
    if recorder == "lcm-logger":
        return programs.lcm_logger(Path(lcm.LCM_BIN_DIR).resolve(), lcm_url=url, log=log_path)
    return programs.auv_recorder(build, lcm_url=url, log=log_path, stats=stats_path)


def recorder_takes_part(sc, recorder: str) -> bool:
    """The world's recorder is a lockstep participant (SIM.RECORDER): the run
    logs, with auv-recorder, on whichever host. Every host must agree: the
    clock's host waits for it and the simulators' configurations name it."""
    return bool(sc.log_enabled) and recorder == "auv-recorder"
