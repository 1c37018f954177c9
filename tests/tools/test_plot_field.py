"""auv-plot-field: any CHANNEL.FIELD of a log against sim time, channels with
dots in their names, nested array columns, and clear refusals."""

from __future__ import annotations

import subprocess
import sys

import lcm

from auv import chasm_status_t, nav_solution_t

PLOT = [sys.executable, "-m", "tools.report.plot_field"]


def _log(path):
    log = lcm.EventLog(str(path), "w", overwrite=True)
    for i in range(20):
        nav = nav_solution_t()
        nav.utime, nav.vehicle, nav.depth_m = i * 100_000, "AUV1", 0.5 * i
        nav.position_cov_m2 = [[float(i), 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        log.write_event(i * 1000, "AUV1.NAV", nav.encode())
        st = chasm_status_t()
        st.utime, st.manager, st.cycle = i * 100_000, "NAVIGATOR", i
        log.write_event(i * 1000 + 1, "AUV1.CHASM.NAVIGATOR", st.encode())
    log.write_event(30_000, "AUV1.NAV", nav.encode()[:-3])
    log.close()


def test_fields_of_any_channel_are_plotted(tmp_path, child_env):
    _log(tmp_path / "r.lcmlog")
    out = tmp_path / "p.png"
    run = subprocess.run(
        PLOT
        + [
            str(tmp_path / "r.lcmlog"),
            "AUV1.NAV.depth_m",
            "AUV1.NAV.position_cov_m2[0][0]",
            "AUV1.CHASM.NAVIGATOR.cycle",
            "--out",
            str(out),
        ],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 1, run.stderr  # the truncated NAV event is reported
    assert "1 undecodable event(s) on AUV1.NAV" in run.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 5000


def test_unknown_channels_and_fields_are_refused_with_a_hint(tmp_path, capsys):
    from tools.report import plot_field  # in-process: one matplotlib import for every case

    _log(tmp_path / "r.lcmlog")
    for spec, text in (
        ("AUV1.NAV.depht_m", "did you mean depth_m"),
        ("AUV1.NAVV.depth_m", "no channel"),
        ("AUV1.NAV.vehicle", "is text, not a number"),
    ):
        assert plot_field.main([str(tmp_path / "r.lcmlog"), spec, "--out", str(tmp_path / "x.png")]) == 2, spec
        assert text in capsys.readouterr().err, spec
        assert not (tmp_path / "x.png").exists()
    assert plot_field.main([str(tmp_path / "none.lcmlog"), "A.B.c"]) == 2
    assert "no such log" in capsys.readouterr().err
