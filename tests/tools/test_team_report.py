"""The report's team section on a synthetic log (lcm.EventLog) whose figures are
worked out by hand below: detection to identification per target, mine-like
targets identified, false identifications, the RI route, link statistics,
bytes per contact, takeovers, and the two team plots."""

from __future__ import annotations

import json
import subprocess
import sys

import lcm

from auv import (
    ground_truth_t,
    modem_rx_t,
    modem_status_t,
    modem_tx_t,
    reacquire_look_t,
    seabed_target_t,
    target_field_t,
    team_event_t,
)

REPORT = [sys.executable, "-m", "tools.report"]
E = team_event_t


def write_log(path):
    log = lcm.EventLog(str(path), "w", overwrite=True)
    seq = [0]

    def put(ch, msg):
        log.write_event(seq[0], ch, msg.encode())
        seq[0] += 1

    tf = target_field_t()
    # 0 mine, 1 mine, 2 clutter, 3 mine never detected
    for i, (n, e, kind) in enumerate([(100, 20, 0), (50, 50, 0), (80, -10, 1), (150, 0, 0)]):
        t = seabed_target_t()
        t.id, t.north_m, t.east_m, t.kind, t.depth_m = i, n, e, kind, 12
        tf.targets.append(t)
    tf.n_targets = 4
    put("SIM.TARGETS", tf)
    for vid in ("AUV1", "AUV2", "AUV4"):
        for k in range(3):
            tr = ground_truth_t()
            tr.utime, tr.vehicle, tr.eta = k * 400_000_000, vid, [10.0 * k, 5.0 * k, 4.0, 0, 0, 0]
            put(f"{vid}.TRUTH", tr)

    def ev(t_s, vid, kind, origin="", number=-1, n=0.0, e=0.0, result=0, text=""):
        m = E()
        m.utime, m.vehicle, m.kind, m.origin, m.number = int(t_s * 1e6), vid, kind, origin, number
        m.north_m, m.east_m, m.result, m.text = n, e, result, text
        put(f"{vid}.TEAM_EVENT", m)

    ev(100, "AUV1", E.CONTACT_NEW, "AUV1", 1, 100.5, 20.5)  # target 0 first seen at 100 s
    ev(101, "AUV1", E.CONTACT_SENT, "AUV1", 1)
    ev(105, "AUV4", E.TARGET_QUEUED, "AUV1", 1, 100.5, 20.5)
    ev(105, "AUV4", E.ROUTE, text="AUV1:1")
    ev(118, "AUV1", E.CONTACT_SENT, "AUV1", 1)  # repeated: not yet acked
    ev(130, "AUV2", E.CONTACT_NEW, "AUV2", 1, 50.0, 50.8)  # target 1 at 130 s
    ev(131, "AUV2", E.CONTACT_SENT, "AUV2", 1)
    ev(160, "AUV2", E.CONTACT_NEW, "AUV2", 2, 99.8, 19.7)  # target 0 again: not its first
    ev(161, "AUV2", E.CONTACT_SENT, "AUV2", 2)
    ev(200, "AUV1", E.CONTACT_NEW, "AUV1", 2, 80.3, -10.2)  # clutter scored mine-like
    ev(201, "AUV1", E.CONTACT_SENT, "AUV1", 2)
    ev(220, "AUV1", E.CONTACT_NEW, "AUV1", 3, 300.0, 300.0)  # a false alarm
    ev(221, "AUV1", E.CONTACT_SENT, "AUV1", 3)
    for origin, number, n, e in (("AUV2", 1, 50.0, 50.8), ("AUV1", 2, 80.3, -10.2), ("AUV1", 3, 300.0, 300.0)):
        ev(225, "AUV4", E.TARGET_QUEUED, origin, number, n, e)
    ev(230, "AUV4", E.ROUTE, text="AUV2:1 AUV1:1 AUV1:2 AUV1:3")
    ev(400, "AUV4", E.TARGET_IDENTIFIED, "AUV1", 1, 100.2, 20.1, E.RESULT_MINE if hasattr(E, "RESULT_MINE") else 1)
    ev(500, "AUV4", E.TARGET_IDENTIFIED, "AUV2", 1, 50.1, 50.2, 2)  # a mine called not mine: false
    ev(600, "AUV4", E.TARGET_IDENTIFIED, "AUV1", 2, 80.0, -10.0, 1)  # clutter called mine: false
    ev(650, "AUV4", E.TARGET_IDENTIFIED, "AUV1", 3, 300.0, 300.0, 2)  # nothing there, not mine: right
    ev(700, "AUV2", E.PEER_LOST, "AUV3")
    ev(700, "AUV2", E.LINES_TAKEN, "AUV3", text="4,5")
    for vid, sent, rec, lost, rs in (("AUV1", 10, 7, 2, 1), ("AUV4", 6, 9, 3, 0)):
        for k in (1, 2):  # the last one counts
            s = modem_status_t()
            s.utime, s.vehicle, s.sent, s.received, s.lost = (
                k * 100_000_000,
                vid,
                sent * k // 2,
                rec * k // 2,
                lost * k // 2,
            )
            s.refused_size, s.last_refusal = rs * k // 2, ""
            put(f"{vid}.MODEM_STATUS", s)
    for src, dst, t_s in (("AUV4", "AUV1", 10), ("AUV4", "AUV1", 30), ("AUV1", "AUV4", 12), ("AUV2", "AUV4", 14)):
        m = modem_rx_t()
        m.utime, m.vehicle, m.src_vehicle, m.kind, m.n_bytes, m.payload = int(t_s * 1e6), dst, src, 2, 1, b"\x00"
        put(f"{dst}.MODEM_RX", m)
    for k, (n, e, result) in enumerate(((100.3, 20.2, 1), (50.2, 49.9, 2), (80.1, -10.0, 2), (0.0, 0.0, 1))):
        m = reacquire_look_t()
        m.utime, m.vehicle, m.look_id, m.north_m, m.east_m, m.result = int(390e6) + k, "AUV4", k + 1, n, e, result
        put("AUV4.LOOKS", m)
    for kind in (2, 2, 2, 0):
        m = modem_tx_t()
        m.utime, m.vehicle, m.kind, m.n_bytes, m.payload = 1, "AUV1", kind, 32, bytes(32)
        put("AUV1.MODEM_TX", m)
    log.close()


def test_team_section_figures_and_plots(tmp_path):
    from tools.report.team_report import contact_bits

    log = tmp_path / "run.lcmlog"
    write_log(log)
    out = tmp_path / "rep"
    run = subprocess.run(REPORT + [str(log), "--out", str(out)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    t = json.loads((out / "report.json").read_text())["team"]
    rows = {r["id"]: r for r in t["targets"]}
    assert (
        rows[0]["detected_s"],
        rows[0]["detected_by"],
        rows[0]["identified_s"],
        rows[0]["result"],
        rows[0]["latency_s"],
    ) == (100, "AUV1", 400, "mine", 300)
    assert (rows[1]["detected_s"], rows[1]["identified_s"], rows[1]["result"], rows[1]["latency_s"]) == (
        130,
        500,
        "not_mine",
        370,
    )
    assert rows[3]["detected_s"] is None and rows[3]["identified_s"] is None
    assert (
        t["mine_like_targets"],
        t["mine_like_detected"],
        t["mine_like_identified"],
        t["mine_like_identified_as_mine"],
        t["identifications"],
    ) == (3, 2, 2, 1, 4)
    assert t["detect_to_identify_s"] == {"mean": 335.0, "median": 335.0, "max": 370.0, "n": 2}
    assert [(f["target"], f["result"], f["truth"]) for f in t["false_identifications"]] == [
        ("AUV2:1", "not_mine", "mine_like"),
        ("AUV1:2", "mine", "clutter"),
    ]
    assert t["ri_vehicles"] == ["AUV4"]
    assert [r["order"] for r in t["routes"]] == [["AUV1:1"], ["AUV2:1", "AUV1:1", "AUV1:2", "AUV1:3"]]
    assert [(x["event"], x["vehicle"], x["peer"], x["text"]) for x in t["takeovers"]] == [
        ("PEER_LOST", "AUV2", "AUV3", ""),
        ("LINES_TAKEN", "AUV2", "AUV3", "4,5"),
    ]
    link = t["link"]["per_vehicle"]
    assert (link["AUV1"]["sent"], link["AUV1"]["heard"], link["AUV1"]["lost"], link["AUV1"]["refused"]) == (10, 7, 2, 1)
    assert (link["AUV4"]["sent"], link["AUV4"]["heard"], link["AUV4"]["lost"]) == (6, 9, 3)
    assert link["AUV1"]["team_frames_queued"] == 3 and link["AUV1"]["team_bytes_queued"] == 96
    bits, _ = contact_bits()
    # AUV1: 4 contact reports (contact 1 twice) for 3 contacts
    assert link["AUV1"]["contacts_reported"] == 3
    assert link["AUV1"]["bytes_per_contact"] == 4 * bits / 8 / 3
    # looks: on mine 0 called mine (right), on mine 1 not mine (wrong), on clutter not mine
    # (right), one on nothing
    assert t["looks"] == {"AUV4": {"looks": 4, "on_objects": 3, "right": 2}}
    assert t["heard"] == {"AUV1->AUV4": 1, "AUV2->AUV4": 1, "AUV4->AUV1": 2}
    text = (out / "report.txt").read_text()
    assert "mine-like targets 3: detected 2, identified by the end 2 (1 as mine)" in text
    assert "FALSE identification at 600 s by AUV4: AUV1:2 called mine, truth clutter" in text
    assert "LINES_TAKEN at 700 s by AUV2: peer AUV3, lines 4,5" in text
    for name in ("heard", "ri_route"):
        assert (out / f"{name}.png").stat().st_size > 5000


def test_contact_size_from_a_schema_file(tmp_path):
    """The spec's contact layout: 4-bit id + 4 + 10 + 14 + 14 + 7 + 7 + 4 + 14 = 78 bits."""
    from tools.report.team_report import contact_bits

    schema = tmp_path / "s.schema"
    schema.write_text(
        "message status 1 max_bytes 12\n  vehicle int 0 15\n"
        "message contact 2 max_bytes 16\n  origin int 0 15\n  number int 0 1023\n"
        "  north_m fixed -2000 2000 0.25\n  east_m fixed -2000 2000 0.25\n"
        "  sigma_m fixed 0 12.7 0.1\n  score fixed 0 1 0.01   # comment\n  looks int 0 15\n"
        "  time_s int 0 16383\nmessage ack 3 max_bytes 4\n  to int 0 15\n"
    )
    import tools.report.team_report as tr

    old = tr.ROOT
    tr.ROOT = tmp_path
    try:
        assert contact_bits(schema)[0] == 78
    finally:
        tr.ROOT = old
    assert contact_bits(tmp_path / "none")[0] == 78  # the built-in copy of the same layout
