"""The console in a real headless browser (Debian's chromium), over a running
scenario: the page loads, shows both vehicles and their managers' state, a
pause round-trips to the manager and back (ack and state on the page); then
the finished log opens with a time slider. Screenshots go to
build/test-artifacts/console/."""

from __future__ import annotations

import json
import subprocess
import sys
import time

from browser import Browser
from console_fixtures import (  # noqa: F401
    ARTIFACTS,
    LAUNCH,
    Console,
    chromium,
    read_until,
    stop_launcher,
    vehicle,
    write_run_log,
    write_scenario,
)


def _panel(vid: str, manager: str, part: str) -> str:
    return (
        f'(document.querySelector(\'.vehicle[data-id="{vid}"] .mgr[data-manager="{manager}"] .{part}\')'
        f" || {{}}).textContent"
    )


def test_live_map_shows_the_run_and_a_pause_round_trips(tmp_path, lcm_url, child_env, chromium):
    # Scaled time, not fast: the page is watched while the mission runs, so sim
    # time must pass at a bounded pace; the launcher is stopped at the end.
    path = write_scenario(
        tmp_path,
        [vehicle("AUV1"), vehicle("AUV2", east=40.0)],
        {"mode": "scaled", "warp": 2, "limit": 600, "wall_limit": 300},
    )
    out = tmp_path / "run"
    launcher = subprocess.Popen(
        LAUNCH + [str(path), "--out", str(out), "--lcm-url", lcm_url, "--progress", "1"],
        env=child_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    # a host agent beside it: the page lists its process table
    agent = subprocess.Popen(
        [sys.executable, "-m", "tools.hosts.agent", "--host", "alpha", "--lcm-url", lcm_url],
        env=child_env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    console = browser = None
    try:
        console = Console(["--lcm-url", lcm_url, "--scenario", str(path)], child_env)
        read_until(launcher, "launch: t=")
        browser = Browser(chromium)
        browser.open(console.url)
        browser.wait_for("document.querySelectorAll('.vehicle').length === 2", what="two vehicles on the page")
        assert browser.eval("[...document.querySelectorAll('.vehicle')].map(e => e.dataset.id)") == ["AUV1", "AUV2"]
        browser.wait_for(f"{_panel('AUV1', 'NAVIGATOR', 'run')} === 'running'", what="AUV1 NAVIGATOR running")
        browser.wait_for(f"{_panel('AUV2', 'NAVIGATOR', 'path')} === 'run'", what="AUV2 NAVIGATOR in run")
        browser.wait_for(
            f"['running', 'done'].includes({_panel('AUV1', 'WATCHER', 'run')})", what="AUV1 WATCHER running or done"
        )
        browser.wait_for(
            "S.world && S.world.seabed && S.world.seabed.depth.length === 40"
            " && S.world.bathymetry_ref.startsWith('slope:')",
            what="the seabed from the scenario",
        )
        browser.wait_for(
            "((document.querySelector('.agent[data-host=\"alpha\"]') || {}).textContent || '').includes('alpha idle')",
            what="host alpha's agent table",
        )
        browser.screenshot(ARTIFACTS / "live.png")

        # Pause AUV1's navigator: a confirmation first, then the ack and the state.
        browser.eval(
            "(() => { const s = document.querySelector('.vehicle[data-id=\"AUV1\"] .mgr-select');"
            " s.value = 'NAVIGATOR'; })()"
        )
        browser.eval('document.querySelector(\'.vehicle[data-id="AUV1"] button[data-cmd="pause"]\').click()')
        assert browser.eval("!document.querySelector('#confirm').hidden")
        assert "Pause AUV1 NAVIGATOR?" in browser.eval("document.querySelector('#confirm-text').textContent")
        browser.screenshot(ARTIFACTS / "confirm.png")
        browser.eval("document.querySelector('#confirm-yes').click()")
        ack = browser.wait_for(
            "(t => t.includes('NAVIGATOR ok') && t)(document.querySelector("
            "'.vehicle[data-id=\"AUV1\"] .ack').textContent)",
            what="the pause ack",
        )
        assert "paused" in ack, ack
        browser.wait_for(f"{_panel('AUV1', 'NAVIGATOR', 'run')} === 'paused'", what="AUV1 NAVIGATOR paused")
        assert browser.eval(_panel("AUV2", "NAVIGATOR", "run")) == "running"
        browser.screenshot(ARTIFACTS / "paused.png")
    finally:
        if browser:
            browser.close()
        if console:
            assert console.stop() == 0
        stop_launcher(launcher)
        agent.terminate()
        agent.wait(timeout=10)

    # The finished log, opened on itself: a slider over its sim time.
    log = out / "run.lcmlog"
    assert log.is_file()
    console = Console(["--log", str(log)], child_env)
    browser = Browser(chromium)
    try:
        browser.open(console.url)
        browser.wait_for("!document.querySelector('#player').hidden", what="the time slider")
        browser.wait_for("document.querySelectorAll('.vehicle').length === 2", what="two vehicles in the log")
        # at the end of the log AUV1's navigator was paused; at 1 s of sim time it ran
        browser.wait_for(f"{_panel('AUV1', 'NAVIGATOR', 'run')} === 'paused'", what="paused at the end")
        assert browser.eval("document.querySelector('.vehicle button') === null")  # no commands on a log
        browser.eval(
            "(() => { const s = document.querySelector('#slider'); s.value = Number(s.min) + 1;"
            " s.dispatchEvent(new Event('input')); })()"
        )
        browser.wait_for(f"{_panel('AUV1', 'NAVIGATOR', 'run')} === 'running'", what="running at t = 1 s")
        t = float(browser.eval("Number(document.querySelector('#slider-time').textContent.split(' ')[0])"))
        assert 0.5 < t < 2.0, t
        browser.screenshot(ARTIFACTS / "log.png")
    finally:
        browser.close()
        assert console.stop() == 0
    print(json.dumps({"screenshots": sorted(p.name for p in ARTIFACTS.glob("*.png"))}))
    time.sleep(0)


def test_the_page_shows_who_flies_a_commercial_vehicle(tmp_path, child_env, chromium):
    """A log where AUV1's frontseat gives our plan control, an operator takes it, and
    it comes back: the vehicle's panel says who has control at each time."""
    write_run_log(tmp_path / "r.lcmlog")
    console = Console(["--log", str(tmp_path / "r.lcmlog")], child_env)
    browser = Browser(chromium)
    fs = "(document.querySelector('.vehicle[data-id=\"AUV1\"] .frontseat') || {}).textContent || ''"
    try:
        browser.open(console.url)
        browser.wait_for("document.querySelectorAll('.vehicle').length === 2", what="two vehicles in the log")
        text = browser.wait_for(
            f"(t => t.includes('payload (our plan) has control') && t)({fs})", what="ours at the end"
        )
        assert "iver3" in text and "mode A" in text and "granted 2" in text and "lost 1" in text, text
        assert browser.eval("document.querySelector('.vehicle[data-id=\"AUV2\"] .frontseat') === null")
        # the log opens at its end, and says so (it once said "disconnected: retrying")
        assert browser.eval("document.querySelector('#mode').textContent") == "log r.lcmlog · end of the log"
        browser.eval(
            "(() => { const s = document.querySelector('#slider'); s.value = 3.5;"
            " s.dispatchEvent(new Event('input')); })()"
        )
        text = browser.wait_for(
            f"(t => t.includes('an operator has control') && t)({fs})", what="the operator's at 3.5 s"
        )
        assert "manual" in text and "mode M" in text, text
        assert browser.eval("document.querySelector('#mode').textContent") == "log r.lcmlog"
        assert browser.eval("!!document.querySelector('.vehicle[data-id=\"AUV1\"] .fs-operator')")
        browser.screenshot(ARTIFACTS / "frontseat.png")
    finally:
        browser.close()
        assert console.stop() == 0
