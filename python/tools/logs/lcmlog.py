#!/usr/bin/env python3
"""Inspect LCM logs with the project's types.

    auv-lcmlog summary LOG                   channels, types, counts, sim-time span, undecodable
    auv-lcmlog csv LOG CHANNEL OUT.csv       one channel: every numeric and string field
    auv-lcmlog csv LOG --all OUTDIR          every channel, one CHANNEL.csv each
    auv-lcmlog npz LOG OUT.npz               every channel's columns, keys "CHANNEL/column"
    auv-lcmlog annotations LOG [--extract DIR]   what the log says about itself
    auv-lcmlog states LOG [CHANNEL_REGEX]    each CHASM's state timeline
    auv-lcmlog mcap LOG OUT.mcap             the log as MCAP for Foxglove (tools/logs/mcap_export.py)

Nested arrays are flattened into columns named as in C (position_cov_m2[0][1]);
variable-length arrays go into one column, elements joined by ';' (arrays of
structs are left out of CSV and named on stderr). A damaged log is read past
the damage (auvlcm.eventlog): what was skipped is printed on stderr.

Exit status: 0 on success; 1 if the log holds events that do not decode or
channel names that are not UTF-8 (counted and reported, never fatal); 3 if
events were lost to a damaged or truncated file (skipped, counted, the rest
read); 2 on a usage or file error (including a file that is not an LCM log).
"""

from __future__ import annotations

import argparse
import csv
import re
import sys
from pathlib import Path

import numpy as np

from auvlcm.arrays import ChannelArrays, LogArrays, load_log
from auvlcm.log import EXIT_EVENTS_LOST, LogStats, damage_lines, read_events
from tools.logs import mcap_export
from tools.logs.timeline import state_timeline


def _show(ch: str) -> str:
    """A channel name safe to print (control characters escaped)."""
    return ch if ch.isprintable() else ch.encode("unicode_escape").decode("ascii")


def _file_name(ch: str) -> str:
    """A channel name as a file name inside the output folder (never a path)."""
    name = re.sub(r"[^A-Za-z0-9_.-]", "_", ch)
    return "_" + name if name.startswith(".") or not name else name


def _damage(path: Path, stats: LogStats) -> int:
    """Print what a damaged log made us skip; the exit status it calls for."""
    for line in damage_lines(path, stats):
        print(line, file=sys.stderr)
    if stats.damage.lost_events:
        return EXIT_EVENTS_LOST
    return 1 if stats.damage.bad_channel_names else 0


def _report_bad(log: LogArrays) -> int:
    for ch, n in sorted(log.undecodable.items()):
        print(f"{log.path}: {n} undecodable event(s) on {_show(ch)}", file=sys.stderr)
    for ch, n in sorted(log.type_conflicts.items()):
        print(f"{log.path}: {n} event(s) of another type on {_show(ch)} (dropped)", file=sys.stderr)
    code = _damage(log.path, log.stats)
    return code or (1 if log.stats.undecodable else 0)


def summary(path: Path) -> int:
    log = load_log(path)
    s = log.stats
    print(
        f"{path}: {s.events} events, {s.decoded} decoded, {s.undecodable} undecodable"
        + (f", {s.internal} liblcm self-test skipped" if s.internal else "")
    )
    print(f"{'channel':32} {'type':24} {'count':>7} {'sim time span [s]':>18}")
    for ch in sorted(s.per_channel):
        arr = log.channels.get(ch)
        span = f"{arr.t.max() - arr.t.min():18.3f}" if arr is not None and len(arr) else f"{'-':>18}"
        print(f"{_show(ch):32} {arr.type_name if arr else '?':24} {s.per_channel[ch]:7d} {span}")
    return _report_bad(log)


def csv_rows(arr: ChannelArrays) -> tuple[list[str], list[list]]:
    """Header and rows of one channel, ragged primitive arrays joined by ';'."""
    ragged = [r for r, v in arr.ragged.items() if not any(x and hasattr(x[0], "__slots__") for x in v)]
    skipped = [r for r in arr.ragged if r not in ragged]
    if skipped:
        print(f"{arr.channel}: not in CSV (variable-length arrays of structs): {', '.join(skipped)}", file=sys.stderr)
    header = ["log_time_us"] + list(arr.columns) + ragged
    cols = [arr.log_time_us] + list(arr.columns.values())
    rows = []
    for i in range(len(arr)):
        row = [c[i].item() if isinstance(c[i], np.generic) else c[i] for c in cols]
        row += [";".join(str(x) for x in arr.ragged[r][i]) for r in ragged]
        rows.append(row)
    return header, rows


def write_csv(arr: ChannelArrays, out: Path) -> None:
    header, rows = csv_rows(arr)
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    print(f"{out}: {len(rows)} rows of {arr.channel}")


def to_csv(path: Path, channel: str | None, out: Path) -> int:
    log = load_log(path, None if channel is None else [channel])
    if channel is not None:
        if channel not in log:
            print(f"{path}: no decodable events on {channel}", file=sys.stderr)
            return 2
        write_csv(log[channel], out)
    else:
        out.mkdir(parents=True, exist_ok=True)
        for ch, arr in log.channels.items():
            write_csv(arr, out / f"{_file_name(ch)}.csv")
    return _report_bad(log)


def to_npz(path: Path, out: Path) -> int:
    log = load_log(path)
    data = {}
    for ch, arr in log.channels.items():
        data[f"{ch}/log_time_us"] = arr.log_time_us
        for name, col in arr.columns.items():
            data[f"{ch}/{name}"] = col.astype(str) if col.dtype == object else col
    np.savez_compressed(out, **data)
    print(f"{out}: {len(data)} arrays from {len(log.channels)} channels")
    return _report_bad(log)


KIND_NAMES = {0: "note", 1: "scenario", 2: "plan", 3: "lcmtype", 4: "event"}


def is_file_annotation(a) -> bool:
    """Scenario, plan and type files, and notes that carry a file (bindings, configs)."""
    return a.kind in (1, 2, 3) or (a.kind == 0 and bool(re.search(r"\.\w+$", a.name)))


def annotations(path: Path, extract: Path | None) -> int:
    n = 0
    stats = LogStats()
    for ev in read_events(path, stats):
        if ev.msg is None or type(ev.msg).__name__ != "log_annotation_t":
            continue
        a = ev.msg
        n += 1
        kind = KIND_NAMES.get(a.kind, str(a.kind))
        first = a.text.splitlines()[0] if a.text else ""
        print(
            f"{a.utime / 1e6:9.2f} s {ev.channel:16} {kind:9} {a.vehicle or '-':6} {a.name}"
            + (f"  {first[:60]}" if a.kind in (0, 4) else f"  ({len(a.text)} chars)")
        )
        if extract is not None and is_file_annotation(a):
            dest = extract / (a.vehicle or "") / a.name.lstrip("/")
            dest.parent.mkdir(parents=True, exist_ok=True)
            dest.write_text(a.text)
    if extract is not None:
        print(f"extracted into {extract}/")
    return _damage(path, stats) or (0 if n else 1)


def states(path: Path, pattern: str) -> int:
    log = load_log(path, pattern)
    if not log.channels:
        print(f"{path}: no CHASM status channel matches {pattern!r}", file=sys.stderr)
        return 2
    for ch, arr in log.channels.items():
        print(ch)
        for seg in state_timeline(arr):
            print(f"  {seg.start:9.2f} s .. {seg.end:9.2f} s  {seg.run:8} {seg.path:32} {seg.condition}")
    return _report_bad(log)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("summary", help="channels, types, counts")
    p.add_argument("log", type=Path)
    p = sub.add_parser("csv", help="export channels as CSV")
    p.add_argument("log", type=Path)
    p.add_argument("channel", nargs="?")
    p.add_argument("out", type=Path, nargs="?")
    p.add_argument("--all", type=Path, metavar="OUTDIR", help="every channel into OUTDIR")
    p = sub.add_parser("npz", help="every channel's columns into one .npz")
    p.add_argument("log", type=Path)
    p.add_argument("out", type=Path)
    p = sub.add_parser("annotations", help="scenario, plans, types and events written into the log")
    p.add_argument("log", type=Path)
    p.add_argument("--extract", type=Path, metavar="DIR", help="write the annotated files into DIR")
    p = sub.add_parser("states", help="state timeline of each CHASM")
    p.add_argument("log", type=Path)
    p.add_argument("pattern", nargs="?", default=r".*\.CHASM\..*")
    mcap_export.add_parser(sub)
    args = parser.parse_args(argv)
    problem = not_a_log(args.log)
    if problem:
        print(f"lcmlog: {args.log}: {problem}", file=sys.stderr)
        return 2
    try:
        return _run(args, parser)
    except OSError as exc:
        print(f"lcmlog: {exc.filename or args.log}: {exc.strerror or exc}", file=sys.stderr)
        return 2


def not_a_log(path: Path) -> str:
    """Why path cannot be read as an LCM log ("" if it can be tried)."""
    from auvlcm.eventlog import SYNC_BYTES

    if not path.is_file():
        return "no such log file"
    try:
        with open(path, "rb") as f:
            head = f.read(1 << 20)
    except OSError as exc:
        return f"cannot read: {exc.strerror}"
    if head and SYNC_BYTES not in head:
        return "not an LCM log (no event header in its first MiB)"
    return ""


def _run(args, parser) -> int:
    if args.cmd == "summary":
        return summary(args.log)
    if args.cmd == "csv":
        if args.all is not None:
            return to_csv(args.log, None, args.all)
        if not args.channel or not args.out:
            parser.error("csv needs CHANNEL OUT.csv, or --all OUTDIR")
        return to_csv(args.log, args.channel, args.out)
    if args.cmd == "npz":
        return to_npz(args.log, args.out)
    if args.cmd == "mcap":
        return mcap_export.run(args)
    if args.cmd == "annotations":
        return annotations(args.log, args.extract)
    return states(args.log, args.pattern)


if __name__ == "__main__":
    sys.exit(main())
