"""The simulator's Micro-Modem emulator (python/sim/devices/micromodem.py) alone,
and face to face with the C bridge (c/drivers/modem, run as build/bin/mm-cli in
both builds): the C formatter's sentences go into the emulator, the emulator's
into the C parser, and a frame crosses each way with its bytes intact."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from sim.devices.micromodem import FRAME_BYTES, FRAMES, MicroModem, checksum, sentence


def lines(data: bytes) -> list[str]:
    return [x for x in data.decode("ascii").split("\r\n") if x]


def bodies(data: bytes) -> list[str]:
    out = []
    for x in lines(data):
        body, _, cs = x[1:].partition("*")
        assert cs == checksum(body), x
        out.append(body)
    return out


def booted(address: int = 1) -> MicroModem:
    m = MicroModem(address=address)
    m.tick(0.0)
    return m


def test_rates_match_the_c_table():
    assert FRAME_BYTES == (32, 64, 64, 256, 256, 256)
    assert FRAMES == (1, 3, 3, 2, 2, 8)


def test_heartbeat():
    m = MicroModem(address=1, heartbeat_s=10.0)
    first = bodies(m.tick(3723.0))
    assert first[0] == "CAREV,010203,INIT,0.94.0.4" and first[1].startswith("CAREV,010203,AUV,")
    assert m.tick(3730.0) == b""
    assert bodies(m.tick(3733.0)) == ["CAREV,010213,AUV,0.94.0.4"]


def test_configuration():
    m = booted()
    assert bodies(m.feed(sentence("CCCFG,SRC,5"), 1.0)) == ["CACFG,SRC,5"]
    assert m.address == 5
    assert bodies(m.feed(sentence("CCCFQ,SRC"), 1.0)) == ["CACFG,SRC,5"]
    assert len(bodies(m.feed(sentence("CCCFQ,ALL"), 1.0))) == len(m.params)
    assert bodies(m.feed(sentence("CCCFG,SRC,300"), 1.0))[0].startswith("CAERR,000001,NMEA,3,bad address")


def test_one_frame_cycle():
    m = booted()
    out = bodies(m.feed(sentence("CCCYC,0,1,2,0,1,1"), 5.0))
    assert out == ["CACYC,0,1,2,0,1,1", "CADRQ,000005,1,2,1,32,1"]
    assert bodies(m.feed(sentence("CCTXD,1,2,1,48656C6C6F"), 5.5)) == ["CATXD,1,2,1,5"]
    (p,) = m.take_outbox()
    assert (p.src, p.dest, p.rate, p.ack, p.frames) == (1, 2, 0, 1, [b"Hello"])
    assert m.take_outbox() == []


def test_three_frames_and_buffered_data():
    m = booted()
    m.feed(sentence("CCTXD,1,2,0,01"), 1.0)  # before the cycle: buffered
    out = bodies(m.feed(sentence("CCCYC,0,1,2,1,0,3"), 1.0))
    assert out[-1] == "CADRQ,000001,1,2,0,64,2"  # frame 1 was buffered
    m.feed(sentence("CCTXD,1,2,0,02"), 1.1)
    m.feed(sentence("CCTXD,1,2,0,03"), 1.2)
    assert m.take_outbox()[0].frames == [b"\x01", b"\x02", b"\x03"]


@pytest.mark.parametrize(
    "line, text",
    [
        (b"$CCCYC,0,1,2,0,1,1*00\r\n", "bad checksum"),
        (sentence("CCXYZ,1"), "unknown sentence CCXYZ"),
        (sentence("CCCYC,0,1,2,9,0,1"), "bad rate"),
        (sentence("CCCYC,0,1,2,0,0,2"), "bad frame count"),
        (sentence("CCCYC,0,3,2,0,0,1"), "ADR1 3 is not this modem"),
        (sentence("CCTXD,1,2,0,ABC"), "odd hex length"),
        (sentence("CCTXD,1,2,0,ZZ"), "bad hex"),
    ],
)
def test_bad_input_answers_caerr(line, text):
    m = booted()
    (err,) = bodies(m.feed(line, 2.0))
    assert err.startswith("CAERR,000002,") and text in err, err
    assert m.errors == 1


def test_data_longer_than_the_frame_and_timeout():
    m = booted()
    m.feed(sentence("CCCYC,0,1,2,0,0,1"), 1.0)
    (err,) = bodies(m.feed(sentence("CCTXD,1,2,0," + "00" * 33), 1.1))
    assert "33 bytes is over the 32-byte frame" in err
    assert bodies(m.tick(7.0)) == ["CAERR,000007,CYC,4,data request timed out"]
    assert m.take_outbox() == []


def test_hear():
    m = booted(address=1)
    out = bodies(m.hear(10.25, src=2, dest=0, rate=0, frames=[b"\xab\xcd"], snr_db=12.5))
    assert out[0] == "CACYC,0,2,0,0,0,1" and out[1] == "CARXD,2,0,0,1,ABCD"
    cst = out[2].split(",")
    assert cst[0] == "CACST" and len(cst) == 30 and cst[13:16] == ["0", "2", "0"] and cst[21] == "12.5"
    assert m.hear(10.0, src=2, dest=3, rate=0, frames=[b"x"], snr_db=1.0) == b""  # for another modem


# ---- face to face with the C bridge


class Bridge:
    def __init__(self, exe: Path, env: dict[str, str], *args: str) -> None:
        self.p = subprocess.Popen(
            [str(exe), "--vehicle", "AUV1", "--table", "AUV1=1,AUV2=2", *args],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            env=env,
            text=True,
        )

    def ask(self, command: str) -> list[str]:
        assert self.p.stdin and self.p.stdout
        self.p.stdin.write(command + "\n")
        self.p.stdin.flush()
        out = []
        while (x := self.p.stdout.readline().rstrip("\n")) != ".":
            assert x, "mm_cli ended"
            out.append(x)
        return out

    def close(self) -> int:
        assert self.p.stdin
        self.p.stdin.close()
        return self.p.wait(timeout=30)


def exchange(bridge: Bridge, modem: MicroModem, first: list[str], t_us: int) -> list[str]:
    """Carries the bridge's writes to the emulator and its answers back until
    neither has more to say; returns every answer line of the bridge."""
    said, todo = [], first
    while todo:
        said += todo
        data = b"".join((x[6:] + "\r\n").encode() for x in todo if x.startswith("write "))
        todo = []
        for line in lines(modem.feed(data, t_us * 1e-6)):
            todo += bridge.ask(f"modem {t_us} {line}")
    return said


@pytest.fixture
def mm_cli(variant_dir):
    exe = variant_dir / "bin" / "mm-cli"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    return exe


def test_c_bridge_and_emulator_agree(mm_cli, child_env):
    b = Bridge(mm_cli, child_env)
    m = MicroModem(address=1)
    said = exchange(b, m, b.ask("start 1000000"), 1000000)
    assert not [x for x in said if x.startswith("bad")], said
    # a frame out: CCCYC -> CADRQ -> CCTXD -> CATXD, and the packet in the water
    payload = bytes(range(32))
    said = exchange(b, m, b.ask(f"send 2000000 7 AUV2 2 {payload.hex()}"), 2000000)
    assert [x for x in said if x.startswith("write")] == [
        "write " + sentence("CCCYC,0,1,2,0,0,1").decode().strip(),
        "write " + sentence("CCTXD,1,2,0," + payload.hex().upper()).decode().strip(),
    ]
    assert any(x.startswith("status sent=1 ") for x in said), said
    (p,) = m.take_outbox()
    assert (p.src, p.dest, p.rate, p.frames) == (1, 2, 0, [payload])
    # a frame in: CACYC, CARXD, CACST -> one modem_rx_t with the SNR
    rx = []
    for line in lines(m.hear(3.0, src=2, dest=0, rate=0, frames=[b"\x01\x02\xff"], snr_db=14.5)):
        rx += b.ask(f"modem 3000000 {line}")
    assert "rx AUV2 - 2 0 14.5 0102FF" in rx, rx
    # the emulator's errors and every sentence it writes parse in C
    for line in lines(m.feed(sentence("CCTXD,1,2,0,ABC"), 4.0) + m.tick(20.0) + m.feed(sentence("CCCFQ,ALL"), 20.0)):
        (answer,) = b.ask(f"parse {line}")
        assert answer.startswith("msg CA"), (line, answer)
    said = b.ask(f"modem 4000000 {lines(m.feed(sentence('CCTXD,1,2,0,ABC'), 4.0))[0]}")
    assert any("modem_errors=1" in x for x in said), said
    assert b.close() == 0


def test_c_bridge_times_out_on_a_silent_modem(mm_cli, child_env):
    b = Bridge(mm_cli, child_env, "--ack")
    said = b.ask("send 1000000 1 AUV2 2 AA")
    assert said[0] == "write " + sentence("CCCYC,0,1,2,0,1,1").decode().strip()
    assert b.ask("send 1500000 2 AUV2 2 AA")[0].startswith("refused busy: frame 1")
    assert any("timeouts=1" in x for x in b.ask("tick 6000000"))
    assert b.close() == 0
