"""The console's state view in a real headless browser (issue 35): a running
scenario's active path appears on its plan's tree and moves when the plan
transitions, the test a transition waits on is named, the finished log
opened at a time t shows the state at t, and a plan file given with --plan
shows its load error beside its state. Screenshots go to
build/test-artifacts/console/ (chasm_view_*.png)."""

from __future__ import annotations

import subprocess

import lcm
from browser import Browser
from conftest import ROOT
from console_fixtures import (  # noqa: F401
    ARTIFACTS,
    LAUNCH,
    Console,
    chromium,
    read_until,
    stop_launcher,
    vehicle,
    write_scenario,
)
from test_chasm_view_model import status, structure

PLAN = ROOT / "tests" / "console" / "plans" / "view.chasm"
COL = "document.querySelector('.cv-col[data-key=\"AUV1/{}\"]')"


def _active(manager: str) -> str:
    """The names of the states drawn active, root first, joined with '/'."""
    return f"[...({COL.format(manager)} || document).querySelectorAll('.cv-col li.active > .nm')].map(e => e.textContent).join('/')"


def _text(manager: str, part: str) -> str:
    return f"(({COL.format(manager)} || document).querySelector('.{part}') || {{}}).textContent || ''"


BAD, GOOD = ROOT / "tests/console/plans/bad_view.chasm", ROOT / "tests/chasm/findings/never_fires.chasm"


def _publish_bad_input(url: str) -> None:
    lc = lcm.LCM(url)
    cyc = structure()
    cyc.manager, cyc.vehicle, cyc.state_parent = "PILOT", "AUV9", [2, 0, 1]
    lc.publish("AUV9.PLAN.PILOT", cyc.encode())
    good = structure()
    good.vehicle = "AUV9"
    lc.publish("AUV9.PLAN.NAVIGATOR", good.encode())
    st = status(plan_id="fedcba9876543210")
    st.vehicle = "AUV9"
    lc.publish("AUV9.CHASM.NAVIGATOR", st.encode())


def _check_plan_files(browser: Browser) -> None:
    """auv-console --plan: the tree as parsed, the load error beside leg2 at its
    file:line:col, and a good plan's `chasm check` summary and findings; nothing runs."""
    col = "document.querySelector('.cv-planfile[data-file=\"{}\"]')"
    browser.wait_for(f"!!{col.format(BAD)}", what="the bad plan's column")
    at = browser.eval(
        f"[...{col.format(BAD)}.querySelectorAll('li')].filter(li => li.querySelector(':scope > .cv-error'))"
        ".map(li => li.querySelector('.nm').textContent + ' ' + li.querySelector(':scope > .cv-error').textContent)"
    )
    assert at == ["leg2 bad_view.chasm:14:22 unknown target state 'nowhere'"], at
    full = f"{col.format(BAD)}.querySelector('.cv-error .cv-loc').title"
    assert browser.eval(full) == f"{BAD}:14:22"
    summary = browser.eval(f"{col.format(GOOD)}.querySelector('.cv-summary').textContent")
    assert "never_fires.chasm: ok (3 states" in summary and "3 findings" in summary, summary
    assert browser.eval(f"{col.format(GOOD)}.querySelectorAll('.cv-finding').length") == 3
    browser.screenshot(ARTIFACTS / "chasm_view_plan_files.png")


def test_state_view_live_and_in_the_log(tmp_path, lcm_url, child_env, chromium):
    auv1 = vehicle("AUV1")
    auv1["managers"][0]["plan"] = str(PLAN)
    del auv1["managers"][0]["params"]
    path = write_scenario(tmp_path, [auv1], {"mode": "scaled", "warp": 2, "limit": 600, "wall_limit": 120})
    out = tmp_path / "run"
    launcher = subprocess.Popen(
        LAUNCH + [str(path), "--out", str(out), "--lcm-url", lcm_url, "--progress", "1"],
        env=child_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    console = browser = None
    try:
        console = Console(["--lcm-url", lcm_url, "--plan", str(BAD), "--plan", str(GOOD)], child_env)
        read_until(launcher, "launch: t=")
        browser = Browser(chromium)
        browser.open(console.url)
        browser.wait_for(f"{_active('NAVIGATOR')} === 'mission/leg1'", what="leg1 active on the tree")
        why = browser.wait_for(
            f"(t => t.includes('counted=false') && t)({_text('NAVIGATOR', 'cv-why')})", what="leg1's test"
        )
        assert "waiting on counted" in why and "nav_stale=false" in why, why
        browser.screenshot(ARTIFACTS / "chasm_view_leg1.png")
        # 160 cycles at 10 Hz (8 s of wall time at x2) later the plan moves on; the tree and the history follow
        browser.wait_for(f"{_active('NAVIGATOR')} === 'mission/leg2'", what="leg2 active on the tree")
        hist = browser.wait_for(f"(t => t.includes('leg2') && t)({_text('NAVIGATOR', 'cv-hist')})", what="the history")
        assert "mission/leg1 → mission/leg2 when counted" in hist, hist
        why = browser.wait_for(
            f"(t => t.includes('waiting on deep') && t)({_text('NAVIGATOR', 'cv-why')})", what="deep"
        )
        assert "leg2 → surface when deep" in why, why
        assert "report" in browser.eval(_text("NAVIGATOR", "cv-status"))
        # the plan's variables with their live values, once opened
        browser.eval(f"{COL.format('NAVIGATOR')}.querySelector('.cv-vars').open = true")
        rows = browser.wait_for(
            f"(t => /input *nav\\.depth_m *-?[0-9.]+ m/.test(t) && t)({_text('NAVIGATOR', 'cv-vars table')})",
            what="nav.depth_m's value",
        )
        assert "output" in rows and "actuators.prop_rpm" in rows and "1500" in rows, rows
        # the second manager, side by side: waits on its own test
        browser.wait_for(f"{_text('WATCHER', 'cv-why')}.includes('waiting on deep')", what="the watcher's test")
        # fold the tree, then "show active" opens it down to the active leaf
        browser.eval(f"{COL.format('NAVIGATOR')}.querySelector('li[data-i=\"0\"] > .tog').click()")
        assert browser.eval(
            f"{COL.format('NAVIGATOR')}.querySelector('li[data-i=\"0\"]').classList.contains('collapsed')"
        )
        browser.eval("document.querySelector('#cv-active').click()")
        assert not browser.eval(
            f"{COL.format('NAVIGATOR')}.querySelector('li[data-i=\"0\"]').classList.contains('collapsed')"
        )
        # bad input from another vehicle: a structure that contradicts itself, and a
        # status of another plan than its structure: counted, not drawn, the reason shown
        _publish_bad_input(lcm_url)
        bad = browser.wait_for(
            "(t => t.includes('refused') && t)((document.querySelector('.cv-col[data-key=\"AUV9/PILOT\"]"
            " .cv-problem') || {}).textContent || '')",
            what="the refused structure",
        )
        assert "1 structure message(s) refused: state 'mission' is its own ancestor" in bad, bad
        other = browser.wait_for(
            "(t => t.includes('not drawn') && t)((document.querySelector('.cv-col[data-key=\"AUV9/NAVIGATOR\"]"
            " .cv-problem') || {}).textContent || '')",
            what="the status of another plan",
        )
        assert "the status is of plan fedcba9876543210, the structure of 0123456789abcdef" in other, other
        assert browser.eval("document.querySelectorAll('.cv-col[data-key=\"AUV9/NAVIGATOR\"] li.active').length") == 0
        # search keeps the matches and their ancestors
        browser.eval(
            "(() => { const s = document.querySelector('#cv-search'); s.value = 'leg2';"
            " s.dispatchEvent(new Event('input')); })()"
        )
        shown = browser.eval(
            f"[...{COL.format('NAVIGATOR')}.querySelectorAll('.cv-tree li')]"
            ".filter(li => !li.hidden).map(li => li.querySelector('.nm').textContent)"
        )
        assert shown == ["mission", "leg2"], shown
        browser.screenshot(ARTIFACTS / "chasm_view_leg2.png")
        _check_plan_files(browser)
    finally:
        if browser:
            browser.close()
        if console:
            assert console.stop() == 0
        stop_launcher(launcher)

    # The log, opened at a time: the view is the machine's state at that time.
    log = out / "run.lcmlog"
    console = Console(["--log", str(log)], child_env)
    browser = Browser(chromium)
    try:
        browser.open(console.url)
        browser.wait_for(f"{_active('NAVIGATOR')} === 'mission/leg2'", what="leg2 at the log's end")
        browser.eval(
            "(() => { const s = document.querySelector('#slider'); s.value = Number(s.min) + 1.5;"
            " s.dispatchEvent(new Event('input')); })()"
        )
        browser.wait_for(f"{_active('NAVIGATOR')} === 'mission/leg1'", what="leg1 at 1.5 s")
        assert "leg2" not in browser.eval(_text("NAVIGATOR", "cv-hist"))
        browser.screenshot(ARTIFACTS / "chasm_view_log.png")
    finally:
        browser.close()
        assert console.stop() == 0
