"""Publishing from a sender thread (auvlcm.sender, c/sender/) changes nothing
the simulator's listeners can see: every message arrives, in order, and the
loop never waits for others with messages still queued. And the simulator is
deterministic: the same seed gives the same messages, bit for bit.
Run inside tests/isolated_net.sh (real LCM, ttl=0)."""

from __future__ import annotations

import contextlib
import gc
import io
import threading
import time
import weakref
from pathlib import Path

import lcm
import pytest

from auv import sim_clock_t
from auvlcm.offline import OfflineLcm
from auvlcm.sender import ThreadedLcm, library_path
from auvlcm.url import with_receive_buffer
from sim.actuators import Command
from sim.config import load
from sim.hil import Simulator
from sim.pilot import Pilot

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "missions" / "sim" / "remus100.yaml"


@pytest.fixture(autouse=True)
def _library():
    if not library_path().exists():
        pytest.fail(f"{library_path()} is not built: run `make build` first")


class Driven(Simulator):
    """The simulator with the pilot (sim.pilot) in the loop, every physics step:
    dives to 25 m on heading 0.5 rad."""

    def __init__(self, *args, **kw) -> None:
        super().__init__(*args, **kw)
        self.ap = Pilot(dt=self.model.dt)

    def _check_stale(self) -> None:
        x = self.model.dyn.x
        self.model.command = Command(
            self.ap.rudder(0.5, x[5], x[11]), self.ap.stern_for_depth(25.0, x[2], x[4], x[10]), 1500.0
        )
        self.last_cmd_t = self.model.t
        super()._check_stale()


def config(seconds: float, url: str = "", clock: str = "realtime", seed: int | None = None):
    cfg = load(CONFIG)
    cfg.sim.duration_s = seconds
    cfg.sim.clock = clock
    if clock == "scaled":
        cfg.sim.warp = 10.0
    cfg.sim.lcm_url = url
    if seed is not None:
        cfg.sim.seed = seed
    return cfg


def run_quiet(sim: Simulator) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        sim.run()
    return out.getvalue()


def recorded(cls, cfg, fast: bool = True) -> list[tuple[str, bytes]]:
    """One in-process run published into a list (HEALTH left out: pid, CPU load)."""
    lc = OfflineLcm()
    try:
        sim = cls(cfg, fast=fast, lc=lc)
        run_quiet(sim)
        sim.close()
    finally:
        lc.close()
    return [(ch, d) for ch, d in lc.published if not ch.endswith(".HEALTH")]


class Listener:
    """Every message on the channels matching pattern, in arrival order.

    It reads from its own thread the whole time, with a large socket buffer: a
    sender running flat out (a fast simulator) must never overflow a receiver
    that only starts reading afterwards, whatever the machine's load (a stress
    run lost 131 of 926 that way)."""

    def __init__(self, url: str, pattern: str) -> None:
        self.lc = lcm.LCM(with_receive_buffer(url))
        self.got: list[tuple[str, bytes]] = []
        sub = self.lc.subscribe(pattern, lambda ch, data: self.got.append((ch, data)))
        sub.set_queue_capacity(100_000)  # liblcm keeps 30 per subscription by default
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self) -> None:
        while not self._stop.is_set():
            self.lc.handle_timeout(20)

    def wait_for(self, n: int, timeout: float = 30.0) -> list[tuple[str, bytes]]:
        deadline = time.monotonic() + timeout
        while len(self.got) < n and time.monotonic() < deadline:
            time.sleep(0.01)
        return list(self.got)

    def close(self) -> None:
        self._stop.set()
        self._thread.join()


@pytest.fixture
def listener():
    """Listener(url, pattern), each closed at the end of the test."""
    made: list[Listener] = []
    yield lambda url, pattern: made.append(Listener(url, pattern)) or made[-1]
    for rx in made:
        rx.close()


def message(i: int) -> tuple[str, bytes]:
    """Message i: one of three channels, 0 to 3000 bytes (fragmented above 1400)."""
    return f"T.CH{i % 3}", bytes((i * 7 + k) % 256 for k in range(i * 37 % 3001))


def test_threaded_lcm_delivers_every_message_in_order(lcm_url, listener):
    rx = listener(lcm_url, r"T\..*")
    tx = ThreadedLcm(lcm_url, slots=4, spin_us=0)  # tiny queue, no spin: every path taken
    sent = []
    for start in range(0, 1500, 100):
        for i in range(start, start + 100):
            sent.append(message(i))
            tx.publish(*sent[-1])
        tx.flush()
        assert tx.pending() == 0
        # a burst at a time, so the receiver's socket buffer can never overflow
        assert len(rx.wait_for(len(sent))) == len(sent)
    st = tx.stats()
    assert st["published"] == st["sent"] == len(sent) and st["send_errors"] == 0
    assert st["full_waits"] > 0 and st["flushes"] == 15
    # close() sends what is still queued; publishing afterwards is an error
    for i in range(1500, 1520):
        sent.append(message(i))
        tx.publish(*sent[-1])
    tx.close()
    with pytest.raises(OSError):
        tx.publish("T.CH0", b"late")
    assert rx.wait_for(len(sent)) == sent
    assert tx.stats()["sent"] == len(sent) and tx.last_error() == ""


def test_the_simulator_sends_through_the_thread_what_the_loop_would(lcm_url, listener):
    """Fast time, 10 s: the threaded run's messages as received over LCM are the
    in-process run's, published from the loop, message for message in order."""
    threaded = config(1.0, lcm_url, "scaled")
    threaded.sim.publish_thread = True  # off by default since the channel filter (docs/simulator.md)
    paced = Simulator(threaded)
    assert not isinstance(paced.lc, ThreadedLcm)  # paced by the wall clock: the loop publishes
    paced.close()
    default = Simulator(config(1.0, lcm_url, "scaled"), fast=True)
    assert not isinstance(default.lc, ThreadedLcm)  # the default
    default.close()
    rx = listener(lcm_url, r"(AUV1|SIM)\..*")
    threaded.sim.duration_s = 10.0
    sim = Simulator(threaded, fast=True)
    assert isinstance(sim.lc, ThreadedLcm)
    summary = run_quiet(sim)
    sim.close()
    assert "0 send errors" in summary
    want = recorded(Simulator, config(10.0, clock="scaled"), fast=True)
    got = [(ch, d) for ch, d in rx.wait_for(sim.published) if not ch.endswith(".HEALTH")]
    assert len(want) > 900 and len({ch for ch, _ in want}) == 11  # the leak probes (LEAK) are the eleventh
    assert len(got) == len(want)
    assert got == want


def test_the_loop_never_waits_with_messages_still_queued(lcm_url):
    """Stepped mode: whenever the simulator blocks for the next SIM.CLOCK, the
    sender thread has sent everything (the clock's owner may be waiting for it)."""
    tx = ThreadedLcm(lcm_url, spin_us=0)  # a sleeping sender: the flush has work to do
    sim = Simulator(config(0.0, lcm_url, "lockstep"), lc=tx)
    pending_at_wait = []
    wait = sim._wait

    def checked_wait(timeout_s: float) -> bool:
        pending_at_wait.append(tx.pending())
        return wait(timeout_s)

    sim._wait = checked_wait

    def clock():
        pub = lcm.LCM(lcm_url)
        for k in range(51):  # 5 s of sim time, 0.1 s steps
            c = sim_clock_t()
            c.utime, c.mode, c.step_us = k * 100_000, sim_clock_t.MODE_LOCKSTEP, 100_000
            pub.publish("SIM.CLOCK", c.encode())
            time.sleep(0.01)
        deadline = time.monotonic() + 30.0
        while sim.model.t < 5.0 - 1e-6 and time.monotonic() < deadline:
            time.sleep(0.01)
        sim.stop_requested = True

    th = threading.Thread(target=clock)
    th.start()
    run_quiet(sim)
    th.join()
    sim.close()
    assert sim.model.t == pytest.approx(5.0)
    assert sim.published > 400 and len(pending_at_wait) > 10
    assert max(pending_at_wait) == 0, pending_at_wait


def test_a_closed_simulator_lets_go_of_its_lcm_instance(lcm_url):
    """liblcm holds the handlers where the garbage collector cannot see them: an
    in-process simulator (bench, tests) that kept its LCM instance would keep a
    receive thread that every later packet wakes."""
    sim = Simulator(config(1.0, lcm_url))
    run_quiet(sim)
    sim.close()
    ref = weakref.ref(sim)
    del sim
    gc.collect()
    assert ref() is None


def test_same_seed_same_messages_another_seed_other_noise():
    a = recorded(Driven, config(30.0))
    b = recorded(Driven, config(30.0))
    c = recorded(Driven, config(30.0, seed=43))
    channels = {ch for ch, _ in a}
    assert {
        "AUV1.AHRS",
        "AUV1.NAV",
        "AUV1.DVL",
        "AUV1.DEPTH",
        "AUV1.ALTIMETER",
        "AUV1.GPS",
        "AUV1.LBL",
        "AUV1.TRUTH",
        "AUV1.ACTUATOR_STATE",
        "SIM.CLOCK",
    } <= channels
    assert a == b
    # the pilot steers by truth: the vehicle moves the same, the instruments differ
    truth = [d for ch, d in a if ch == "AUV1.TRUTH"]
    assert truth == [d for ch, d in c if ch == "AUV1.TRUTH"]
    for ch in ("AUV1.AHRS", "AUV1.NAV", "AUV1.DVL", "AUV1.DEPTH"):
        mine = [d for x, d in a if x == ch]
        other = [d for x, d in c if x == ch]
        assert len(mine) == len(other) and mine != other, ch


def test_send_failures_are_counted_and_reported_once(lcm_url):
    """Sends happen on the sender thread: a failure is counted, and the owner hears
    of it when it asks (the simulator asks at each HEALTH), once."""
    tx = ThreadedLcm(lcm_url)
    tx.publish("T." + "X" * 100, b"abc")  # liblcm refuses channels over 63 characters
    tx.publish("T.OK", b"abc")
    tx.flush()
    st = tx.stats()
    assert st["sent"] == 2 and st["send_errors"] == 1
    assert "1 messages lost so far" in tx.new_errors()
    assert tx.new_errors() == ""
    tx.close()
    assert "1 send errors" in tx.summary()
