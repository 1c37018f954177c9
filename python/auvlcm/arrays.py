"""An LCM log as numpy arrays, one table per channel.

Every numeric field becomes a column; fixed-size arrays and nested structs
are flattened into columns named as in C (`position_cov_m2[0][1]`,
`pose.north_m`); strings are object columns; variable-length arrays (whose
size differs from message to message) are kept per message in `ragged`.
Events that do not decode are counted per channel and dropped, never fatal.

    log = load_log("run.lcmlog")
    nav = log["AUV1.NAV"]
    nav.t, nav["north_m"], nav["position_cov_m2[0][0]"]
"""

from __future__ import annotations

import operator
import re
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterable

import numpy as np

from auvlcm.log import LogStats, read_events
from auvlcm.types import by_name

_NUMERIC = {
    "int8_t": np.int64,
    "int16_t": np.int64,
    "int32_t": np.int64,
    "int64_t": np.int64,
    "byte": np.int64,
    "float": np.float64,
    "double": np.float64,
    "boolean": np.bool_,
}


@dataclass
class Column:
    name: str  # C-style path, e.g. "position_cov_m2[0][1]"
    expr: str  # Python expression on message `m`
    dtype: Any  # numpy dtype, or object for strings


@dataclass
class Layout:
    """How one message type flattens: fixed columns and variable-length fields."""

    columns: list[Column]
    ragged: list[str]  # fields with a variable length (dotted inside a nested struct)
    row: Callable[[Any], tuple]  # message -> values of `columns`, in order


def _walk(cls: type, prefix: str, expr: str, cols: list[Column], ragged: list[str]) -> None:
    for name, tname, dims in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__):
        path, code = f"{prefix}{name}", f"{expr}.{name}"
        if dims and any(not isinstance(d, int) for d in dims):
            ragged.append(path)  # size read from another field: differs per message
            continue
        for index in _indices(dims or []):
            sub = "".join(f"[{i}]" for i in index)
            if tname in _NUMERIC:
                cols.append(Column(path + sub, code + sub, _NUMERIC[tname]))
            elif tname == "string":
                cols.append(Column(path + sub, code + sub, object))
            else:  # a nested struct of fixed size: its fields, prefixed
                _walk(by_name(tname), f"{path}{sub}.", code + sub, cols, ragged)


def _indices(dims: list[int]) -> list[tuple[int, ...]]:
    out: list[tuple[int, ...]] = [()]
    for d in dims:
        out = [i + (j,) for i in out for j in range(d)]
    return out


_layouts: dict[type, Layout] = {}


def layout(cls: type) -> Layout:
    """The flattening of a message type, built once from lcm-gen's type information."""
    if cls not in _layouts:
        cols: list[Column] = []
        ragged: list[str] = []
        _walk(cls, "", "m", cols, ragged)
        # One compiled tuple expression per type: an order of magnitude faster
        # than getattr loops on logs of hundreds of thousands of events.
        src = "lambda m: (" + "".join(f"{c.expr}, " for c in cols) + ")"
        _layouts[cls] = Layout(cols, ragged, eval(src))  # noqa: S307 - built from field names
    return _layouts[cls]


@dataclass
class ChannelArrays:
    """One channel's messages as columns; `t` is the messages' own sim time [s]."""

    channel: str
    type_name: str
    log_time_us: np.ndarray  # the logging host's receive time
    columns: dict[str, np.ndarray]
    ragged: dict[str, list]  # variable-length fields, one list per message

    def __len__(self) -> int:
        return len(self.log_time_us)

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.columns[name]
        except KeyError:
            raise KeyError(f"{self.channel} ({self.type_name}) has no column {name!r}") from None

    @property
    def t(self) -> np.ndarray:
        return self.columns["utime"] / 1e6 if "utime" in self.columns else self.log_time_us / 1e6


@dataclass
class LogArrays:
    path: Path
    channels: dict[str, ChannelArrays]
    stats: LogStats
    undecodable: Counter = field(default_factory=Counter)  # per channel
    type_conflicts: Counter = field(default_factory=Counter)  # other types on a channel
    messages: dict[str, list] = field(default_factory=dict)  # kept decoded messages
    events_to_mark: int | None = None  # events up to and with the first load_log(mark=) found

    def __getitem__(self, channel: str) -> ChannelArrays:
        try:
            return self.channels[channel]
        except KeyError:
            raise KeyError(f"{self.path}: no decodable events on {channel}") from None

    def __contains__(self, channel: str) -> bool:
        return channel in self.channels

    def matching(self, pattern: str) -> list[str]:
        """Channel names that fully match a regular expression, sorted."""
        rx = re.compile(pattern)
        return sorted(c for c in self.channels if rx.fullmatch(c))


class _Builder:
    def __init__(self, channel: str, cls: type) -> None:
        self.channel, self.cls, self.layout = channel, cls, layout(cls)
        self.rows: list[tuple] = []
        self.ragged: dict[str, list] = {r: [] for r in self.layout.ragged}
        # a nested struct's variable field too ("auth.mac": command_auth_t's MAC)
        self.ragged_get = {r: operator.attrgetter(r) for r in self.layout.ragged}
        self.log_time: list[int] = []

    def add(self, timestamp: int, msg: Any) -> None:
        self.log_time.append(timestamp)
        self.rows.append(self.layout.row(msg))
        for r in self.ragged:
            self.ragged[r].append(list(self.ragged_get[r](msg)))

    def build(self) -> ChannelArrays:
        cols: dict[str, np.ndarray] = {}
        by_col = list(zip(*self.rows)) if self.rows else [()] * len(self.layout.columns)
        for col, values in zip(self.layout.columns, by_col):
            cols[col.name] = np.array(values, dtype=col.dtype)
        return ChannelArrays(
            self.channel, self.cls.__name__, np.array(self.log_time, dtype=np.int64), cols, self.ragged
        )


def load_log(
    path: str | Path,
    channels: str | Iterable[str] | None = None,
    keep_messages: str | None = None,
    mark: Callable[[Any], bool] | None = None,
) -> LogArrays:
    """Read a log into arrays.

    channels: a regular expression or a list of names to load (default: all).
    keep_messages: a regular expression of channels whose decoded messages are
    also kept (e.g. "SIM.TARGETS|.*CONTACTS") in `messages`.
    mark: a test of a decoded event; `events_to_mark` counts the events up to
    and with the first that passes it (None: none did).
    """
    if channels is None:
        want: Callable[[str], bool] = lambda _c: True
    elif isinstance(channels, str):
        rx = re.compile(channels)
        want = lambda c: rx.fullmatch(c) is not None
    else:
        names = set(channels)
        want = names.__contains__
    keep = re.compile(keep_messages) if keep_messages else None
    stats = LogStats()
    out = LogArrays(Path(path), {}, stats)
    builders: dict[str, _Builder] = {}
    for ev in read_events(path, stats):
        if mark is not None and out.events_to_mark is None and ev.msg is not None and mark(ev):
            out.events_to_mark = stats.events
        if not want(ev.channel):
            continue
        if ev.msg is None:
            out.undecodable[ev.channel] += 1
            continue
        b = builders.get(ev.channel)
        if b is None:
            b = builders[ev.channel] = _Builder(ev.channel, type(ev.msg))
        elif type(ev.msg) is not b.cls:  # one type per channel is the rule; count the rest
            out.type_conflicts[ev.channel] += 1
            continue
        b.add(ev.timestamp, ev.msg)
        if keep is not None and keep.fullmatch(ev.channel):
            out.messages.setdefault(ev.channel, []).append(ev.msg)
    out.channels = {c: b.build() for c, b in sorted(builders.items())}
    return out
