"""What the vehicle's radio gateway costs (docs/radio.md): auv-radio on a TCP byte
pipe, a plugin upload of almost 4 MiB (the largest it takes) in 4 KiB chunks
written as fast as it reads them, until the whole is published on LCM. Prints
the wall time and the gateway's own CPU (every chunk framed, CRC-checked,
decoded, written to the spool, answered; the whole read back, its SHA-256, the
LCM publish). The radio itself (115200 bit/s) takes about 5 minutes for it.

    tests/isolated_net.sh .venv/bin/python bench/radio_bench.py
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import lcm

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

from tools.radio.outbox import Outbox  # noqa: E402
from tools.radio.pipe import encode  # noqa: E402
from tools.radio.wire import frame  # noqa: E402

URL = "udpm://239.255.76.67:7990?ttl=0&recv_buf_size=8388608"


def cpu_s(pid: int) -> float:
    with open(f"/proc/{pid}/schedstat") as f:
        return int(f.read().split()[0]) * 1e-9


def main() -> int:
    exe = ROOT / "build" / "bin" / "auv-radio"
    if not exe.exists():
        print(f"{exe} not built: run `make build`", file=sys.stderr)
        return 1
    listener = socket.create_server(("127.0.0.1", 0))
    with tempfile.TemporaryDirectory() as spool:
        cmd = [str(exe), "--tcp", f"127.0.0.1:{listener.getsockname()[1]}", "--vehicle", "AUV1"]
        cmd += ["--clock", "system", "--lcm-url", URL, "--spool", spool]
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        conn, _ = listener.accept()
        proc.stdout.readline()  # ready
        lc = lcm.LCM(URL)
        got: list[bytes] = []
        lc.subscribe("AUV1.PLUGIN_UPLOAD", lambda c, d: got.append(d))
        data = os.urandom(4 * 1024 * 1024 - 100)
        box = Outbox("AUV1", chunk_bytes=4096, window=10**6)
        box.submit("PLUGIN_UPLOAD", data, 1, "bench", 0.0).tid = 5
        box.heard(0.0)
        chunks = box.due(0.0, 0)
        stream = b"".join(encode(frame("SHORE", "AUV1", i, 0, c.encode())) for i, c in enumerate(chunks))
        conn.setblocking(False)
        c0, t0, sent = cpu_s(proc.pid), time.monotonic(), 0
        while not got and time.monotonic() - t0 < 120:
            if sent < len(stream):
                try:
                    sent += conn.send(stream[sent : sent + 65536])
                except BlockingIOError:
                    pass
            try:
                conn.recv(1 << 20)  # its acks
            except BlockingIOError:
                pass
            lc.handle_timeout(1)
        wall, cpu = time.monotonic() - t0, cpu_s(proc.pid) - c0
        proc.terminate()
        proc.wait()
    ok = bool(got) and got[0] == data
    print(f"auv-radio: {len(data) / 2**20:.1f} MiB upload in {len(chunks)} chunks of 4 KiB: {wall:.2f} s wall,")
    print(
        f"  {cpu:.2f} s of its CPU ({len(data) / 2**20 / max(cpu, 1e-9):.1f} MiB per CPU second), whole {'ok' if ok else 'MISSING'}"
    )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
