"""A hostile corpus of log files, generated from a real small log: every log
reader (auvlcm.log, auv-lcmlog's subcommands, auv-report) reads past damage,
says what it skipped and exits with the documented status, never a traceback.

The source log is synthetic_log() of test_report (written by lcm.EventLog).
"""

from __future__ import annotations

import struct
import subprocess
import sys

import pytest
from test_report import synthetic_log

from auvlcm.eventlog import HEADER, SYNC_BYTES, read_raw
from auvlcm.log import EXIT_EVENTS_LOST, LogStats, read_events

LCMLOG = [sys.executable, "-m", "tools.logs.lcmlog"]
REPORT = [sys.executable, "-m", "tools.report"]


@pytest.fixture(scope="module")
def good(tmp_path_factory):
    path = tmp_path_factory.mktemp("log") / "good.lcmlog"
    synthetic_log(path)
    data = path.read_bytes()
    offsets = [e.offset for e in read_raw(path)]
    return data, offsets


def _events(data: bytes, tmp_path, name="x.lcmlog"):
    p = tmp_path / name
    p.write_bytes(data)
    stats = LogStats()
    evs = list(read_events(p, stats))
    return p, evs, stats


def _flip(data: bytes, at: int, value: int) -> bytes:
    return data[:at] + bytes([value]) + data[at + 1 :]


def test_intact_log_reads_whole(good, tmp_path):
    data, offsets = good
    _, evs, stats = _events(data, tmp_path)
    assert len(evs) == len(offsets) > 1000 and not stats.damage.any


@pytest.mark.parametrize("field,at", [("sync", 0), ("number", 4), ("channel length", 23), ("data length", 27)])
def test_a_corrupt_header_mid_log_loses_one_event_and_the_rest_is_read(good, tmp_path, field, at):
    data, offsets = good
    mid = offsets[len(offsets) // 2]
    bad = _flip(data, mid + at, data[mid + at] ^ 0x5A)
    _, evs, stats = _events(bad, tmp_path)
    lost = len(offsets) - len(evs)
    if field == "number":  # a wrong number does not break the chain: nothing lost
        assert lost == 0
        return
    assert lost == 1, (field, lost)
    assert stats.damage.lost_events == 1 and stats.damage.skipped_bytes > 0
    i = offsets.index(mid)
    assert mid <= stats.damage.regions[0][0] < offsets[i + 1]


def test_huge_and_zero_lengths_and_garbage_between_events(good, tmp_path):
    data, offsets = good
    a, b = offsets[100], offsets[700]
    bad = bytearray(data)
    struct.pack_into(">i", bad, a + 24, 0x7FFFFFFF)  # huge data length
    struct.pack_into(">i", bad, b + 20, 0)  # zero channel length
    c = offsets[900]
    bad = bytes(bad[:c]) + b"\x00garbage" + SYNC_BYTES + b"\xff" * 40 + bytes(bad[c:])
    _, evs, stats = _events(bytes(bad), tmp_path)
    assert len(evs) == len(offsets) - 2
    assert stats.damage.lost_events == 2 and len(stats.damage.regions) == 3


def test_truncated_at_every_region_of_an_event(good, tmp_path):
    data, offsets = _small(good)
    last = offsets[-1]
    for cut in [0, 1, 4, 12, 20, HEADER.size, HEADER.size + 3, len(data) - last - 1]:
        _, evs, stats = _events(data[: last + cut], tmp_path)
        assert len(evs) == len(offsets) - 1
        assert stats.damage.lost_events == (1 if cut else 0)
        assert stats.damage.truncated == bool(cut)


def test_bad_utf8_in_a_channel_name_is_kept_and_counted(good, tmp_path):
    data, offsets = good
    at = offsets[5] + HEADER.size  # first byte of the channel name
    _, evs, stats = _events(_flip(data, at, 0xFF), tmp_path)
    assert len(evs) == len(offsets) and stats.damage.bad_channel_names == 1
    assert sum("\ufffd" in e.channel for e in evs) == 1


def test_empty_and_non_log_files(tmp_path):
    _, evs, stats = _events(b"", tmp_path)
    assert evs == [] and not stats.damage.any
    _, evs, stats = _events(b"name: not a log\n" * 100, tmp_path)
    assert evs == [] and stats.damage.skipped_bytes == 1600


def _tools(path, tmp_path):
    out = tmp_path / "out"
    return {
        "summary": LCMLOG + ["summary", str(path)],
        "csv": LCMLOG + ["csv", str(path), "AUV1.TRUTH", str(tmp_path / "t.csv")],
        "csv --all": LCMLOG + ["csv", str(path), "--all", str(out)],
        "npz": LCMLOG + ["npz", str(path), str(tmp_path / "o.npz")],
        "annotations": LCMLOG + ["annotations", str(path)],
        "states": LCMLOG + ["states", str(path)],
        "report": REPORT + [str(path), "--out", str(out), "--no-plots"],
    }


def _run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=120)


def _small(good):
    """The first 1500 events: the tools run as processes, keep them quick."""
    data, offsets = good
    return data[: offsets[1500]], offsets[:1500]


def test_every_log_tool_reports_lost_events_and_exits_3(good, tmp_path):
    data, offsets = _small(good)
    mid = offsets[len(offsets) // 2]
    bad = _flip(_flip(data, mid + 27, data[mid + 27] ^ 0x40), offsets[3] + HEADER.size, 0xFE)
    path = tmp_path / "damaged.lcmlog"
    path.write_bytes(bad)
    assert EXIT_EVENTS_LOST == 3
    for name, cmd in _tools(path, tmp_path).items():
        run = _run(cmd)
        assert "Traceback" not in run.stderr, (name, run.stderr)
        assert run.returncode == 3, (name, run.returncode, run.stderr)
        assert "damaged: skipped" in run.stderr and "1 event(s) lost" in run.stderr, (name, run.stderr)
        assert "not UTF-8" in run.stderr, (name, run.stderr)


def test_bad_channel_name_alone_is_reported_not_fatal(good, tmp_path):
    data, offsets = _small(good)
    path = tmp_path / "name.lcmlog"
    path.write_bytes(_flip(data, offsets[3] + HEADER.size, 0xFE))
    run = _run(LCMLOG + ["summary", str(path)])
    assert run.returncode == 1 and "Traceback" not in run.stderr and "not UTF-8" in run.stderr
    run = _run(REPORT + [str(path), "--out", str(tmp_path / "o"), "--no-plots"])
    assert run.returncode == 0 and "Traceback" not in run.stderr, run.stderr


def test_not_a_log_and_empty_file_give_2_with_a_reason(tmp_path):
    junk = tmp_path / "junk.lcmlog"
    junk.write_bytes(b"\x7fELF" + bytes(range(256)) * 10)
    for name, cmd in _tools(junk, tmp_path).items():
        run = _run(cmd)
        assert run.returncode == 2 and "not an LCM log" in run.stderr and "Traceback" not in run.stderr, name
    empty = tmp_path / "empty.lcmlog"
    empty.write_bytes(b"")
    run = _run(LCMLOG + ["summary", str(empty)])
    assert run.returncode == 0 and "0 events" in run.stdout
    run = _run(REPORT + [str(empty), "--no-plots", "--out", str(tmp_path / "e")])
    assert run.returncode == 2 and "no vehicle" in run.stderr and "Traceback" not in run.stderr


def test_hostile_channel_names_never_escape_the_csv_folder(tmp_path):
    import lcm

    from auv import depth_t

    p = tmp_path / "names.lcmlog"
    log = lcm.EventLog(str(p), "w", overwrite=True)
    for i, ch in enumerate(["../escape", "/abs", ".hidden", "A\x1b[2J"]):
        log.write_event(i, ch, depth_t().encode())
    log.close()
    run = _run(LCMLOG + ["csv", str(p), "--all", str(tmp_path / "o")])
    assert run.returncode == 0, run.stderr
    assert sorted(x.name for x in (tmp_path / "o").iterdir()) == sorted(
        ["_.._escape.csv", "_.hidden.csv", "_abs.csv", "A__2J.csv"]
    )
    assert not (tmp_path / "escape.csv").exists()
    run = _run(LCMLOG + ["summary", str(p)])
    assert "\x1b" not in run.stdout


def test_whole_events_cut_out_are_found_by_their_numbers(good, tmp_path):
    data, offsets = _small(good)
    cut = data[: offsets[100]] + data[offsets[150] :]  # 50 sound events removed cleanly
    _, evs, stats = _events(cut, tmp_path)
    assert len(evs) == len(offsets) - 50
    assert stats.damage.lost_events == 50 and stats.damage.number_gaps == 1 and not stats.damage.skipped_bytes
    assert "the event numbers jump 1 time(s)" in stats.damage.lines("x")[0]
    bad = bytearray(data)  # one damaged number field: nothing lost
    struct.pack_into(">q", bad, offsets[200] + 4, 7)
    _, evs, stats = _events(bytes(bad), tmp_path)
    assert len(evs) == len(offsets) and stats.damage.lost_events == 0
    _, evs, stats = _events(data + data, tmp_path)  # two logs joined: numbers restart
    assert len(evs) == 2 * len(offsets) and not stats.damage.any
