"""Inspect LCM logs with the project's types.

    python python/tools/lcmlog.py summary LOG          channels, counts, types, sim-time span
    python python/tools/lcmlog.py csv LOG CHANNEL OUT  one channel's scalar fields as CSV

Exit status: 0 on success, 1 if the log holds events that do not decode
(they are reported, never silently skipped), 2 on a usage or file error.
"""

from __future__ import annotations

import argparse
import csv
import sys
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from auvlcm.log import LogStats, read_events  # noqa: E402


def scalar_fields(msg) -> dict[str, object]:
    """Flatten a message's scalar and fixed-array fields into columns."""
    row: dict[str, object] = {}
    for name in msg.__slots__:
        value = getattr(msg, name)
        if isinstance(value, (int, float, str, bool)):
            row[name] = value
        elif isinstance(value, (list, tuple)) and all(isinstance(v, (int, float)) for v in value):
            for i, v in enumerate(value):
                row[f"{name}[{i}]"] = v
        elif isinstance(value, (list, tuple)) and value and isinstance(value[0], (list, tuple)):
            for i, rowv in enumerate(value):
                for j, v in enumerate(rowv):
                    if isinstance(v, (int, float)):
                        row[f"{name}[{i}][{j}]"] = v
    return row


def summary(log: Path) -> int:
    stats = LogStats()
    types: dict[str, str] = {}
    span: dict[str, list[int]] = defaultdict(list)
    for ev in read_events(log, stats):
        if ev.msg is None:
            print(f"undecodable event on {ev.channel}: {ev.error}", file=sys.stderr)
            continue
        types[ev.channel] = type(ev.msg).__name__
        utime = getattr(ev.msg, "utime", None)
        if isinstance(utime, int):
            span[ev.channel].append(utime)
    print(f"{log}: {stats.events} events, {stats.decoded} decoded, {stats.undecodable} undecodable")
    print(f"{'channel':32} {'type':24} {'count':>7} {'sim time span [s]':>18}")
    for ch in sorted(stats.per_channel):
        t = span.get(ch) or [0]
        print(f"{ch:32} {types.get(ch, '?'):24} {stats.per_channel[ch]:7d} "
              f"{(max(t) - min(t)) / 1e6:18.3f}")
    return 1 if stats.undecodable else 0


def to_csv(log: Path, channel: str, out: Path) -> int:
    rows = [scalar_fields(ev.msg) for ev in read_events(log) if ev.channel == channel and ev.msg]
    if not rows:
        print(f"{log}: no decodable events on {channel}", file=sys.stderr)
        return 2
    with open(out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print(f"{out}: {len(rows)} rows of {channel}")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("summary")
    p.add_argument("log", type=Path)
    p = sub.add_parser("csv")
    p.add_argument("log", type=Path)
    p.add_argument("channel")
    p.add_argument("out", type=Path)
    args = parser.parse_args(argv)
    if not args.log.is_file():
        print(f"lcmlog: {args.log}: no such log file", file=sys.stderr)
        return 2
    if args.cmd == "summary":
        return summary(args.log)
    return to_csv(args.log, args.channel, args.out)


if __name__ == "__main__":
    sys.exit(main())
