"""The run's recorder: its command line and whether it takes part in the clock.

One definition for every host that may record: the launcher (`launch.py`, its
own log) and a host agent (`agent_part.py`, when the scenario logs on its
host). Both start the recorder the scenario names (`logging.recorder`):
auv-recorder (c/recorder: loses nothing it receives, counts what the kernel
dropped, and in a lockstep world is the participant SIM.RECORDER, so time
waits for it) or lcm-logger (its subscription queue holds 30 messages and
drops messages of a busy fast-time run).
"""

from __future__ import annotations

from pathlib import Path

import lcm

from auvlcm.url import with_receive_buffer


def recorder_cmd(recorder: str, url: str, log_path: Path, stats_path: Path, build: Path) -> list[str]:
    """The command that records url into log_path (auv-recorder also writes its
    counts to stats_path at exit)."""
    url = with_receive_buffer(url)
    if recorder == "lcm-logger":
        lcm_bin = Path(lcm.LCM_BIN_DIR).resolve()
        return [str(lcm_bin / "lcm-logger"), f"--lcm-url={url}", "--quiet", "--flush-interval=100", "-f", str(log_path)]
    return [str(build / "bin" / "auv-recorder"), "--url", url, "-f", str(log_path), "--stats", str(stats_path)]


def recorder_takes_part(sc, recorder: str) -> bool:
    """The world's recorder is a lockstep participant (SIM.RECORDER): the run
    logs, with auv-recorder, on whichever host. Every host must agree: the
    clock's host waits for it and the simulators' configurations name it."""
    return bool(sc.log_enabled) and recorder == "auv-recorder"
