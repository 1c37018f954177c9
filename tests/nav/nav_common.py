"""Helpers shared by the navigation tests: recording a simulated survey with
auv-nav running live beside it, replaying logs, reading truth."""

from __future__ import annotations

import bisect
import math
import signal
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from conftest import BUILD, ROOT

from auvlcm.log import read_events

SURVEY_LOG = ("-m", "tools.nav.survey_log")
NAVCONF = ("-m", "tools.nav.navconf")
SURVEY_CONFIG = ROOT / "missions" / "sim" / "remus100_survey.yaml"
SANITIZER_EXITS = (86, 87)


@dataclass
class Recording:
    log: Path
    nav_config: Path
    nav_stderr: str
    nav_rc: int


def record_survey(
    out_dir: Path,
    url: str,
    env: dict,
    args: list[str],
    live_nav: Path | None = None,
    nav_channel: str = "AUV1.NAV_EKF",
    timeout: float = 600,
) -> Recording:
    """auv-survey-log with `args`; if live_nav is a binary, auv-nav runs beside it."""
    out_dir.mkdir(parents=True, exist_ok=True)
    log = out_dir / "survey.lcmlog"
    sets = [a for i, a in enumerate(args) if i > 0 and args[i - 1] == "--set"]
    sim_yaml = out_dir / "survey.sim.yaml"
    # the nav config the filter gets: derived from the same (overridden) world
    from auvlcm.url import with_receive_buffer
    from tools.nav.survey_log import apply_overrides

    sim_yaml.write_text(apply_overrides(SURVEY_CONFIG.read_text(), sets))
    nav_cfg = out_dir / "survey.nav"
    subprocess.run([sys.executable, *NAVCONF, sim_yaml, "-o", nav_cfg], env=env, check=True, timeout=60)
    nav = None
    if live_nav is not None:
        nav = subprocess.Popen(
            [
                live_nav,
                "--config",
                nav_cfg,
                "--vehicle",
                "AUV1",
                "--channel",
                nav_channel,
                "--clock",
                "sim",
                "--rate",
                "10",
                "--lcm-url",
                with_receive_buffer(url),
            ],
            env=env,
            stderr=subprocess.PIPE,
            text=True,
        )
    try:
        run = subprocess.run(
            [sys.executable, *SURVEY_LOG, "--out", log, "--lcm-url", url, *args],
            env=env,
            capture_output=True,
            text=True,
            timeout=timeout,
        )
        assert run.returncode == 0, run.stdout + run.stderr
    finally:
        rc, err = 0, ""
        if nav is not None:
            nav.send_signal(signal.SIGTERM)
            try:
                _, err = nav.communicate(timeout=30)
            except subprocess.TimeoutExpired:
                nav.kill()
                _, err = nav.communicate()
            rc = nav.returncode
    return Recording(log, nav_cfg, err, rc)


def replay(config: Path, log: Path, *extra, variant: Path = BUILD) -> dict[str, float | str]:
    """Run auv-nav-replay; its `key value` summary as a dict (numbers as floats)."""
    exe = variant / "bin" / "auv-nav-replay"
    p = subprocess.run(
        [exe, "--config", config, "--log", log, *map(str, extra)], capture_output=True, text=True, timeout=300
    )
    assert p.returncode not in SANITIZER_EXITS, p.stderr
    assert p.returncode == 0, p.stdout + p.stderr
    out: dict[str, float | str] = {}
    for line in p.stdout.splitlines():
        key, _, value = line.rpartition(" ")
        try:
            out[key] = float(value)
        except ValueError:
            out[key] = value
    return out


class TruthTrack:
    """Ground truth from a log, interpolated in time (positions NED)."""

    def __init__(self, log: Path, vehicle: str = "AUV1") -> None:
        self.t: list[float] = []
        self.p: list[tuple[float, float, float]] = []
        self.current: list[tuple[float, float]] = []
        for ev in read_events(log):
            if ev.channel == f"{vehicle}.TRUTH" and ev.msg is not None:
                self.t.append(ev.msg.utime / 1e6)
                self.p.append(tuple(ev.msg.eta[0:3]))
                self.current.append(tuple(ev.msg.current_ned_mps[0:2]))

    def at(self, t: float) -> tuple[float, float, float]:
        i = min(max(bisect.bisect_left(self.t, t), 1), len(self.t) - 1)
        t0, t1 = self.t[i - 1], self.t[i]
        w = 0.0 if t1 == t0 else min(max((t - t0) / (t1 - t0), 0.0), 1.0)
        a, b = self.p[i - 1], self.p[i]
        return tuple(a[k] + w * (b[k] - a[k]) for k in range(3))

    def index(self, t: float) -> int:
        return min(bisect.bisect_left(self.t, t - 1e-6), len(self.t) - 1)


def horizontal(a, b) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])
