#!/usr/bin/env python3
"""Plot any numeric field of any channel of a log against sim time.

    auv-plot-field LOG CHANNEL.FIELD [CHANNEL.FIELD ...] [--out FILE.png|.svg]

A field is named as `auv-lcmlog csv` names its column: `AUV1.NAV.depth_m`,
`AUV1.NAV.position_cov_m2[0][0]`, `AUV1.TRUTH.eta[2]`, `SIM.CLOCK.step`.
Channels hold dots too; the longest channel of the log that starts the name
wins. One panel per field, sharing the time axis; each channel's own colour
stays the same between runs (it comes from the channel's name).

Exit status: 0 written; 1 the log has undecodable events on a plotted channel
(reported, the plot is still written); 2 usage, unknown channel or field,
or a field that is not a number.
"""

from __future__ import annotations

import argparse
import difflib
import sys
import zlib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from auvlcm.arrays import load_log

PALETTE = plt.get_cmap("tab10").colors


class FieldError(ValueError):
    pass


def _candidates(spec: str) -> list[tuple[str, str]]:
    """Every (channel, field) split of a name at a dot, longest channel first."""
    parts = spec.split(".")
    return [(".".join(parts[:i]), ".".join(parts[i:])) for i in range(len(parts) - 1, 0, -1)]


def resolve(log, spec: str) -> tuple[str, str]:
    for channel, fieldname in _candidates(spec):
        if channel in log:
            arr = log[channel]
            if fieldname not in arr.columns:
                close = difflib.get_close_matches(fieldname, list(arr.columns), n=3)
                hint = (
                    f" (did you mean {', '.join(close)}?)"
                    if close
                    else f"; its fields: {', '.join(list(arr.columns)[:20])}"
                )
                raise FieldError(f"{spec}: {channel} ({arr.type_name}) has no field {fieldname!r}{hint}")
            if arr.columns[fieldname].dtype == object:
                raise FieldError(f"{spec}: {fieldname} is text, not a number")
            return channel, fieldname
    chans = list(log.channels)
    close = difflib.get_close_matches(spec.rsplit(".", 1)[0], chans, n=3)
    hint = f" (did you mean {', '.join(close)}?)" if close else ""
    raise FieldError(f"{spec}: no channel of the log starts this name{hint}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="auv-plot-field", description=__doc__.split("\n\n")[0])
    ap.add_argument("log", type=Path)
    ap.add_argument("fields", nargs="+", metavar="CHANNEL.FIELD")
    ap.add_argument("--out", type=Path, help="PNG or SVG (default: the first field's name .png)")
    args = ap.parse_args(argv)
    if not args.log.is_file():
        print(f"plot_field: {args.log}: no such log file", file=sys.stderr)
        return 2
    wanted = {c for spec in args.fields for c, _ in _candidates(spec)}
    log = load_log(args.log, wanted)
    try:
        picks = [resolve(log, spec) for spec in args.fields]
    except FieldError as exc:
        print(f"plot_field: {exc}", file=sys.stderr)
        return 2
    out = args.out or Path(args.fields[0].replace("/", "_") + ".png")
    fig, axes = plt.subplots(len(picks), 1, sharex=True, squeeze=False, figsize=(9, 2.2 + 1.8 * len(picks)))
    for ax, (channel, fieldname) in zip(axes[:, 0], picks):
        arr = log[channel]
        y = arr.columns[fieldname].astype(float)
        colour = PALETTE[zlib.crc32(channel.encode()) % len(PALETTE)]
        ax.plot(
            arr.t,
            y,
            color=colour,
            lw=1.2,
            drawstyle="steps-post" if arr.columns[fieldname].dtype != float else "default",
        )
        ax.set_ylabel(fieldname)
        ax.set_title(f"{channel} ({arr.type_name})", fontsize=9, loc="left")
        ax.grid(alpha=0.3)
        if not np.isfinite(y).any():
            ax.text(0.5, 0.5, "no finite values", transform=ax.transAxes, ha="center")
    axes[-1, 0].set_xlabel("sim time [s]")
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    print(f"{out}: {', '.join(args.fields)}")
    bad = {c: log.undecodable[c] for c, _ in picks if log.undecodable[c]}
    for c, n in bad.items():
        print(f"{args.log}: {n} undecodable event(s) on {c}", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
