"""Where a device's bytes go: a pseudo-terminal or a TCP server, both non-blocking.

    PtyTransport(link)        a pty; its slave's path published as the symlink `link`
    TcpTransport(host, port)  a TCP server, one client at a time

The port's writer thread (sim.devices.port) is the only caller. A transport
says whether anyone is listening (connected()): a pty whose slave nobody has
open, or a server with no client, takes no bytes (the port counts them as
unheard) and keeps no stale ones for the next reader, as a serial line does. A
client that leaves is replaced by the next one the server accepts.
"""

from __future__ import annotations

import array
import errno
import fcntl
import os
import select
import socket
import termios
import time
import tty
from pathlib import Path

LINGER_QUIET_S = 0.05  # a pty reader's queue empty this long: it has taken everything


class Transport:
    """What the port's thread uses: fds to wait on, reading, sending, closing."""

    connects = 0  # readers or clients that came (a pty: opens of its slave noticed)
    disconnects = 0

    def read_fds(self) -> list[int]:
        """Descriptors to wait on for input (or for a client to come)."""
        return []

    def connected(self) -> bool:
        return False

    def on_readable(self, fd: int) -> bytes:
        """Bytes the far end sent (b"" if none); accepts or drops clients as needed."""
        return b""

    def send(self, data: bytes) -> int:
        """Hand data on without blocking; how many bytes were taken."""
        return 0

    def linger(self, timeout_s: float) -> None:
        """Before closing: give a reader up to timeout_s to take what was handed on."""

    def close(self) -> None:
        pass

    def describe(self) -> str:
        return ""


def _nonblocking(fd: int) -> None:
    fcntl.fcntl(fd, fcntl.F_SETFL, fcntl.fcntl(fd, fcntl.F_GETFL) | os.O_NONBLOCK)


class PtyTransport(Transport):
    """A pseudo-terminal in raw mode (no echo, no line editing: the bytes as sent).

    The slave is what a driver opens, by the symlink. Whether one has it open is
    the master's POLLHUP: with no reader the bytes are not written (they would
    wait in the kernel for the next reader, seconds old), and what a reader left
    unread is flushed when it closes.
    """

    def __init__(self, link: str | Path) -> None:
        self.link = Path(link)
        self.master, slave = os.openpty()
        self.slave_name = os.ttyname(slave)
        tty.setraw(slave)
        os.close(slave)
        _nonblocking(self.master)
        self._poll = select.poll()
        self._poll.register(self.master, select.POLLOUT)
        self._was_connected = False
        self.link.parent.mkdir(parents=True, exist_ok=True)
        tmp = self.link.with_name(f".{self.link.name}.{os.getpid()}.tmp")
        if tmp.is_symlink() or tmp.exists():
            tmp.unlink()
        os.symlink(self.slave_name, tmp)
        os.replace(tmp, self.link)  # atomic: a reader never sees the link half made

    def connected(self) -> bool:
        ev = self._poll.poll(0)
        now = bool(ev) and not ev[0][1] & select.POLLHUP
        if now != self._was_connected:
            self._was_connected = now
            if now:
                self.connects += 1
            else:
                self.disconnects += 1
                self._flush_unread()
        return now

    def _flush_unread(self) -> None:
        """Drop what the last reader left in the slave's input queue."""
        try:
            fd = os.open(self.slave_name, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        except OSError:
            return
        try:
            termios.tcflush(fd, termios.TCIOFLUSH)
        finally:
            os.close(fd)

    def read_fds(self) -> list[int]:
        return [self.master] if self._was_connected else []

    def on_readable(self, fd: int) -> bytes:
        try:
            return os.read(self.master, 4096)
        except BlockingIOError:
            return b""
        except OSError as e:  # EIO: the reader closed the slave
            if e.errno != errno.EIO:
                raise
            return b""

    def send(self, data: bytes) -> int:
        try:
            return os.write(self.master, data)
        except BlockingIOError:
            return 0  # the reader's queue is full: it does not keep up
        except OSError as e:
            if e.errno != errno.EIO:
                raise
            return 0

    def linger(self, timeout_s: float) -> None:
        """Closing the master hangs the slave up, and its unread input with it:
        wait (up to timeout_s) until the reader has taken it (FIONREAD on the slave)."""
        if not self._was_connected:
            return
        try:
            probe = os.open(self.slave_name, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        except OSError:
            return
        try:
            deadline = time.monotonic() + timeout_s
            unread = array.array("i", [0])
            empty_since = None
            while time.monotonic() < deadline:
                fcntl.ioctl(probe, termios.FIONREAD, unread, True)
                now = time.monotonic()
                if unread[0]:
                    empty_since = None
                elif empty_since is None:
                    empty_since = now
                elif now - empty_since >= LINGER_QUIET_S:  # the kernel passes bytes on with a delay
                    break
                time.sleep(0.005)
        finally:
            os.close(probe)

    def close(self) -> None:
        try:
            if self.link.is_symlink() and os.readlink(self.link) == self.slave_name:
                self.link.unlink()
        except OSError:
            pass
        os.close(self.master)

    def describe(self) -> str:
        return f"pty {self.link} -> {self.slave_name}"


class TcpTransport(Transport):
    """A TCP server on host:port: one client at a time, the next accepted when it leaves."""

    def __init__(self, host: str, port: int) -> None:
        self.server = socket.create_server((host, port), reuse_port=False, backlog=4)
        self.server.setblocking(False)
        self.address = self.server.getsockname()[:2]
        self.client: socket.socket | None = None

    def connected(self) -> bool:
        return self.client is not None

    def read_fds(self) -> list[int]:
        return [self.client.fileno() if self.client is not None else self.server.fileno()]

    def on_readable(self, fd: int) -> bytes:
        if self.client is None:
            try:
                conn, _ = self.server.accept()
            except (BlockingIOError, ConnectionError):
                return b""
            conn.setblocking(False)
            conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            self.client = conn
            self.connects += 1
            return b""
        try:
            data = self.client.recv(4096)
        except BlockingIOError:
            return b""
        except OSError:
            data = b""
        if not data:
            self._drop()
        return data

    def _drop(self) -> None:
        if self.client is not None:
            self.client.close()
            self.client = None
            self.disconnects += 1

    def send(self, data: bytes) -> int:
        if self.client is None:
            return 0
        try:
            return self.client.send(data)
        except BlockingIOError:
            return 0
        except OSError:
            self._drop()
            return 0

    def close(self) -> None:
        self._drop()
        self.server.close()

    def describe(self) -> str:
        return f"tcp {self.address[0]}:{self.address[1]}"
