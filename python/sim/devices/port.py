"""A device's port: the line's bursts handed to a transport by a writer thread.

The simulation never waits for a port. write() queues a burst (sim.devices.line)
and returns; a queue over its bound refuses the burst and counts it
(`overflows`). A thread of the port's own hands each byte to the transport when
the line's clock (sim.devices.clocks) reaches the byte's sim time, reads what
the far end sends into an inbox the simulator empties (take_input()), and
watches for readers and clients coming and going.

Bytes that find no one listening are counted as `unheard`; bytes a reader
does not take fast enough (its kernel queue full) as `lost`: a UART's overrun.
"""

from __future__ import annotations

import math
import os
import select
import threading
from collections import deque

from sim.devices.clocks import LineClock
from sim.devices.line import Burst, Line
from sim.devices.transport import Transport

MIN_WAIT_S = 0.002  # the writer's finest wake-up: a few bytes at 9600 baud
IDLE_WAIT_S = 0.05  # how often an idle writer looks for a reader coming
INBOX_BYTES = 65536  # input kept for the simulator between two of its steps
LINGER_S = 0.5  # at close, how long a reader has to take the last bytes handed on


class Port:
    def __init__(self, transport: Transport, line: Line, clock: LineClock, queue_bytes: int = 65536) -> None:
        self.transport = transport
        self.line = line
        self.clock = clock
        self.queue_bytes = queue_bytes
        self._queue: deque[Burst] = deque()
        self._queued = 0  # bytes in the queue not yet handed on
        self._inbox = bytearray()
        self._lock = threading.Lock()  # the queue and the inbox
        self._io = threading.Lock()  # the transport: the writer thread, or flush_due() from a step
        self._wake_r, self._wake_w = os.pipe()
        os.set_blocking(self._wake_r, False)
        os.set_blocking(self._wake_w, False)
        self.messages = 0  # bursts queued
        self.overflows = 0  # bursts refused: the queue was full
        self.sent = 0  # bytes a reader took
        self.unheard = 0  # bytes nobody was listening to
        self.lost = 0  # bytes the reader did not take in time
        self.received = 0  # bytes the far end sent
        self.inbox_overflows = 0  # of those, dropped: the simulator did not take them
        self.error = ""  # what stopped the writer thread, if anything did
        self._stop = False
        self._thread = threading.Thread(target=self._run, name=f"port {transport.describe()}", daemon=True)
        self._thread.start()

    # ------------------------------------------------ the simulator's side
    def write(self, data: bytes, t_measured: float) -> Burst | None:
        """Queue data, measured at sim time t_measured; None if the queue is full."""
        with self._lock:
            if self._queued + len(data) > self.queue_bytes:
                self.overflows += 1
                return None
            burst = self.line.burst(data, t_measured, self.clock.now())
            self._queue.append(burst)
            self._queued += len(data)
            self.messages += 1
        self.wake()
        return burst

    def take_input(self) -> bytes:
        """What the far end sent since the last call."""
        with self._lock:
            data = bytes(self._inbox)
            self._inbox.clear()
        return data

    def pending(self) -> int:
        """Bytes queued and not yet handed on."""
        with self._lock:
            return self._queued

    def flush_due(self) -> None:
        """Hand on the bytes due by the clock's time now, from the caller's thread: a
        stepped simulator's bytes of a step are out before it reports the step done."""
        with self._io:
            data, _ = self._due_bytes()
            if data:
                self._hand_on(data)

    def wake(self) -> None:
        """Tell the writer to look again (a burst queued, a step clock moved)."""
        try:
            os.write(self._wake_w, b"!")
        except BlockingIOError:
            pass  # the pipe is full of wake-ups already

    def close(self) -> None:
        self._stop = True
        self.wake()
        self._thread.join(2.0)
        self.transport.linger(LINGER_S)
        self.transport.close()
        os.close(self._wake_r)
        os.close(self._wake_w)

    # ------------------------------------------------- the writer thread
    def _due_bytes(self) -> tuple[bytes, float]:
        """The bytes due by the clock's time now, and the sim time the next one is."""
        now = self.clock.now()
        out = bytearray()
        with self._lock:
            while self._queue:
                b = self._queue[0]
                n = b.due(now)
                if n > b.sent:
                    out += b.data[b.sent : n]
                    self._queued -= n - b.sent
                    b.sent = n
                if b.sent < len(b.data):
                    return bytes(out), b.next_byte_t() - now
                self._queue.popleft()
        return bytes(out), math.inf

    def _hand_on(self, data: bytes) -> None:
        if not self.transport.connected():
            self.unheard += len(data)
            return
        n = self.transport.send(data)
        self.sent += n
        self.lost += len(data) - n

    def _timeout(self, next_in: float) -> float:
        if not self.transport.connected() and not self.transport.read_fds():
            cap = IDLE_WAIT_S  # a pty: poll for a reader opening it
        else:
            cap = 0.5
        if math.isinf(next_in):
            return cap
        wall = self.clock.wall_s(next_in)
        return cap if wall is None else min(max(wall, MIN_WAIT_S), cap)

    def _run(self) -> None:
        try:
            while True:
                # read before the clock: the bytes of a closing simulator's last step go out
                stopping = self._stop
                with self._io:
                    data, next_in = self._due_bytes()
                    if data:
                        self._hand_on(data)
                    timeout = self._timeout(next_in)
                    fds = self.transport.read_fds()
                if stopping:
                    break
                try:
                    ready, _, _ = select.select([self._wake_r, *fds], [], [], timeout)
                except (OSError, ValueError):  # a client a step's write dropped meanwhile
                    continue
                for fd in ready:
                    if fd == self._wake_r:
                        while True:
                            try:
                                if not os.read(self._wake_r, 512):
                                    break
                            except BlockingIOError:
                                break
                    else:
                        with self._io:
                            data = self.transport.on_readable(fd)
                        self._take(data)
        except Exception as e:  # noqa: BLE001 - reported in the summary, never kills the simulation
            self.error = f"{type(e).__name__}: {e}"

    def _take(self, data: bytes) -> None:
        if not data:
            return
        self.received += len(data)
        with self._lock:
            room = INBOX_BYTES - len(self._inbox)
            if len(data) > room:
                self.inbox_overflows += len(data) - room
                data = data[:room]
            self._inbox += data

    def summary(self) -> str:
        err = f", writer stopped: {self.error}" if self.error else ""
        return (
            f"{self.transport.describe()} at {self.line.baud} baud: {self.messages} messages, "
            f"{self.sent} bytes sent, {self.unheard} unheard, {self.lost} lost, "
            f"{self.overflows} queue overflows, {self.received} bytes received, "
            f"{self.transport.connects} connects{err}"
        )
