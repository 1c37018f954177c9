"""Where the console's model gets its messages: live LCM, or a finished log.

LiveSource receives on its own thread (the only thread that calls handle())
and publishes operator commands (liblcm's publish is thread-safe). Only the
channels the console draws are subscribed, so liblcm drops the rest in C.
LogSource reads a log once, keeps the messages the console draws, and moves
the model to any time: forward by applying what is new, backward by starting
over.
"""

from __future__ import annotations

import bisect
import re
import struct
import threading
from pathlib import Path
from typing import Any

import lcm

from auvlcm import auth
from auvlcm.decode import DecodeError, decode_strict
from auvlcm.types import type_of
from auvlcm.url import with_receive_buffer
from tools.console import mission_commands
from tools.console.model import CHANNELS, WALL_STAMPED, Model
from tools.console.world import WorldBuilder

WORLD_TYPES = ("log_annotation_t", "env_model_t")
THINNED = (".TRUTH", ".NAV")  # high-rate channels a log keeps every THIN_US only
THIN_US = 100_000


def decode(data: bytes) -> Any | None:
    cls = type_of(data)
    if cls is None:
        return None
    try:
        return decode_strict(cls, data)
    except DecodeError:
        return None


class LiveSource:
    mode = "live"

    def __init__(
        self, model: Model, world: WorldBuilder, url: str, ring: auth.KeyRing | None = None, command_prefix: str = ""
    ) -> None:
        self.model, self.world = model, world
        self.command_prefix = command_prefix  # "SHORE.": commands go through the radio's shore gateway
        self.ring = ring  # commands are signed with it (docs/security.md); None: not authenticated
        self.sender = auth.default_sender("console")
        # a large receive buffer: a fleet's managers send their plan structures (tens of kB each) at once
        self.lc = lcm.LCM(with_receive_buffer(url))
        self.decode_errors = 0
        self._seq = mission_commands.first_seq()
        self._seq_lock = threading.Lock()
        self._stop = threading.Event()
        sub = self.lc.subscribe(CHANNELS, self._on_raw)
        sub.set_queue_capacity(2000)
        self.thread = threading.Thread(target=self._run, name="lcm-rx", daemon=True)

    def start(self) -> None:
        self.thread.start()

    def stop(self) -> None:
        self._stop.set()
        self.thread.join(timeout=2)

    def _run(self) -> None:
        while not self._stop.is_set():
            self.lc.handle_timeout(200)

    def _on_raw(self, channel: str, data: bytes) -> None:
        msg = decode(data)
        if msg is None:
            self.decode_errors += 1
            self.model.refuse_structure(channel, "a message that is no chasm_structure_t (unknown type or bad length)")
            return
        if type(msg).__name__ in WORLD_TYPES:
            self.world.observe(channel, msg)
        else:
            self.model.apply(channel, msg)

    def next_seq(self) -> int:
        with self._seq_lock:
            self._seq += 1
            return self._seq

    def command(self, vehicle: str, manager: str, name: str, plan_name: str = "", plan_text: str = "") -> int:
        """Publish one mission command; the ack arrives in the model. Returns its seq."""
        seq = self.next_seq()
        utime = int(self.model.t * 1e6)
        msg = mission_commands.command(
            vehicle, manager, name, seq, utime, plan_name, plan_text, reason=f"console ({mission_commands.who()})"
        )
        if self.ring:
            auth.sign(msg, self.ring, self.sender)
        self.lc.publish(f"{self.command_prefix}{vehicle}.MISSION_CMD", msg.encode())
        return seq


class LogSource:
    """A finished log with a time slider: seek(t) shows the world at sim time t."""

    mode = "log"

    def __init__(self, model: Model, world: WorldBuilder, path: Path) -> None:
        self.model, self.world, self.path = model, world, path
        keep = re.compile(CHANNELS)
        self.times: list[float] = []
        self.events: list[tuple[str, Any]] = []
        self.decode_errors = 0
        self.thinned = 0
        last_kept: dict[str, int] = {}
        t = 0.0
        log = lcm.EventLog(str(path), "r")
        try:
            for ev in log:
                if not keep.fullmatch(ev.channel):
                    continue
                if ev.channel.endswith(THINNED) and len(ev.data) >= 16:
                    # the map needs positions every THIN_US, not at the sensors' rate: read
                    # utime (the first field of both types) without decoding the rest
                    utime = struct.unpack(">q", ev.data[8:16])[0]
                    if 0 <= utime - last_kept.get(ev.channel, -THIN_US) < THIN_US:
                        self.thinned += 1
                        continue
                    last_kept[ev.channel] = utime
                msg = decode(ev.data)
                if msg is None:
                    self.decode_errors += 1
                    continue  # (a bad structure in a log shows as no structure: the view says so)
                if type(msg).__name__ in WORLD_TYPES:
                    world.observe(ev.channel, msg)  # the layers do not change with time
                    continue
                # log order, monotonic time; a wall-stamped table (a host agent's)
                # shows at the sim time it was recorded at
                utime = getattr(msg, "utime", 0) if type(msg).__name__ not in WALL_STAMPED else 0
                t = max(t, utime / 1e6)
                self.times.append(t)
                self.events.append((ev.channel, msg))
        finally:
            log.close()
        self.start_t = self.times[0] if self.times else 0.0
        self.end_t = self.times[-1] if self.times else 0.0
        self.cursor = 0  # events applied so far
        self.lock = threading.Lock()

    def start(self) -> None:
        self.seek(self.end_t)

    def stop(self) -> None:
        pass

    def seek(self, t: float) -> float:
        t = min(max(t, self.start_t), self.end_t)
        with self.lock:
            upto = bisect.bisect_right(self.times, t)
            if upto < self.cursor:
                self.model.clear()
                self.cursor = 0
            for channel, msg in self.events[self.cursor : upto]:
                self.model.apply(channel, msg)
            self.cursor = upto
            with self.model.lock:
                self.model.t = t
                self.model.version += 1
                self.model.lock.notify_all()
        return t

    def command(self, *args: Any, **kwargs: Any) -> int:
        raise PermissionError("a log cannot be commanded")
