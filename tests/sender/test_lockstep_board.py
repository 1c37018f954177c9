"""The lockstep clock's board (c/common/lockstep_board.c, auvlcm/lockstep_board.py).

- It takes exactly the reports Python would have turned into a first report
  of a known participant's next step, no later than the limit: checked against
  Python's own decoder on well-formed, hostile and mutated messages.
- Over real LCM, on a FilteredLcm's own socket: Python's handlers get every
  other message, in order; a wait returns when the watched step's last report
  came, and not for a report that leaves someone owing it.
"""

from __future__ import annotations

import random
import struct
import time

import lcm
import pytest

from auv import lockstep_t
from auvlcm import chanfilter, lockstep_board
from sim.multihil.lockstep import decode_lockstep, lockstep_msg

K = lockstep_t
FP = lockstep_t._get_packed_fingerprint()


@pytest.fixture
def lib():
    lib = chanfilter._load()
    if lib is None:
        pytest.skip("libauvlcm_sender.so is not built")
    return lib


def report(name: str, step: int, kind: int = K.KIND_STEP_DONE) -> bytes:
    return lockstep_msg(name, kind, step, max(0, min(step, 10**9)) * 50_000).encode()


def python_would_take(board_state: dict[str, int], limit: int, channel: str, data: bytes) -> bool:
    """What the board must decide, from Python's decoder and the clock's rules."""
    if channel != "SIM.LOCKSTEP":
        return False
    try:
        m = decode_lockstep(data)
    except ValueError:
        return False
    if m.kind != K.KIND_STEP_DONE or m.participant not in board_state:
        return False
    return board_state[m.participant] < m.step <= limit


def test_it_takes_a_known_participants_next_step_and_nothing_else(lib):
    b = lockstep_board.LockstepBoard(lib, "SIM.LOCKSTEP", FP)
    b.put("AUV1.sim", -1)
    b.put("AUV1.PILOT", -1)
    b.set_limit(1)
    assert b.take("SIM.LOCKSTEP", report("AUV1.sim", 0))
    assert b.last_done("AUV1.sim") == 0
    assert not b.take("SIM.LOCKSTEP", report("AUV1.sim", 0))  # a repeat: Python counts it
    assert not b.take("SIM.LOCKSTEP", report("AUV1.sim", 2))  # never published
    assert not b.take("SIM.LOCKSTEP", report("AUV9.sim", 0))  # unknown: Python registers it
    assert not b.take("SIM.LOCKSTEP", report("AUV1.PILOT", 0, K.KIND_REGISTER))
    assert not b.take("SIM.LOCKSTEP", report("AUV1.PILOT", 0, K.KIND_LEAVE))
    assert not b.take("OTHER", report("AUV1.PILOT", 0))
    assert b.take("SIM.LOCKSTEP", report("AUV1.PILOT", 1))  # a step skipped is still progress
    assert b.last_done("AUV1.PILOT") == 1 and b.last_done("AUV9.sim") is None
    assert b.taken == 2


def test_owing_counts_and_names_in_the_order_put(lib):
    b = lockstep_board.LockstepBoard(lib, "SIM.LOCKSTEP", FP)
    for n in ("C", "A", "B"):
        b.put(n, 4)
    b.put("A", 5)
    assert b.owing(5) == 2 and b.owing_names(5) == ["C", "B"]
    assert b.owing(4) == 0 and b.owing_names(4) == []
    b.remove("C")
    b.remove("nobody")
    assert b.owing_names(5) == ["B"] and b.last_done("C") is None
    long_name = "X" * 1000  # matched whole, listed cut
    b.put(long_name, -1)
    assert b.last_done(long_name) == -1 and b.owing_names(0)[-1] == "X" * 255


def test_its_decisions_agree_with_pythons_decoder_on_hostile_input(lib):
    b = lockstep_board.LockstepBoard(lib, "SIM.LOCKSTEP", FP)
    state = {"AUV1.sim": 3, "AUV1.NAV": 3, "é": 3}
    rng = random.Random(7)
    good = [report(n, s, k) for n in (*state, "AUV2.sim", "") for s in (-5, 3, 4, 5, 2**62) for k in (0, 1, 2, 9)]
    head = FP + struct.pack(">q", 0)
    crafted = [
        b"",
        FP,
        head + struct.pack(">i", 0) + struct.pack(">bq", 1, 4),  # an empty length: no NUL
        head + struct.pack(">i", -1) + b"AUV1.sim\0" + struct.pack(">bq", 1, 4),
        head + struct.pack(">i", 9) + b"AUV1.sim\0" + struct.pack(">bq", 1, 4) + b"\0",  # a byte too many
        head + struct.pack(">i", 9) + b"AUV1.sim\0" + struct.pack(">bq", 1, 4)[:-1],  # a byte short
        head + struct.pack(">i", 9) + b"AUV1.simX" + struct.pack(">bq", 1, 4),  # no NUL
        head + struct.pack(">i", 10) + b"AUV1.sim\0\0" + struct.pack(">bq", 1, 4),  # a NUL inside
        b"\0" * 8 + report("AUV1.sim", 4)[8:],  # another type's fingerprint
    ]
    cases = [("SIM.LOCKSTEP", d) for d in good + crafted] + [("SIM.LOCKSTEPX", report("AUV1.sim", 4))]
    for _ in range(3000):  # mutations of a report the board would take
        d = bytearray(report(rng.choice(list(state)), 4))
        for _ in range(rng.randint(1, 3)):
            op = rng.random()
            i = rng.randrange(len(d))
            if op < 0.6:
                d[i] = rng.randrange(256)
            elif op < 0.8:
                del d[i]
            else:
                d.insert(i, rng.randrange(256))
        cases.append(("SIM.LOCKSTEP", bytes(d)))
    taken = 0
    for channel, data in cases:
        for n, s in state.items():
            b.put(n, s)
        b.set_limit(5)
        want = python_would_take(state, 5, channel, data)
        assert b.take(channel, data) == want, (channel, data)
        taken += want
    assert taken > 30  # the property was tested on takes too, not only on refusals


def test_python_gets_every_message_the_board_does_not_take_in_order(own_lcm, lcm_url):
    board = lockstep_board.attach(own_lcm, "SIM.LOCKSTEP", FP)
    assert board is not None
    got: list[tuple[str, object]] = []
    own_lcm.subscribe("SIM.LOCKSTEP", lambda c, d: got.append((c, decode_lockstep(d).participant)))
    own_lcm.subscribe("OTHER", lambda c, d: got.append((c, d)))
    board.put("A", -1)
    board.put("B", -1)
    board.set_limit(1)
    board.set_watch(0)
    pub = lcm.LCM(lcm_url)
    pub.publish("SIM.LOCKSTEP", report("A", 0))  # taken: B still owes step 0
    pub.publish("OTHER", b"x")
    pub.publish("SIM.LOCKSTEP", report("C", 0, K.KIND_REGISTER))
    pub.publish("SIM.LOCKSTEP", report("A", 0))  # a repeat
    pub.publish("SIM.LOCKSTEP", report("B", 0))  # taken: the last report of step 0
    results = []
    deadline = time.monotonic() + 10
    while board.last_done("B") != 0 and time.monotonic() < deadline:
        results.append(own_lcm.handle_timeout(2000))
    assert got == [("OTHER", b"x"), ("SIM.LOCKSTEP", "C"), ("SIM.LOCKSTEP", "A")]
    assert results[-1] == 1 and board.taken == 2 and board.owing(0) == 0


def test_a_wait_ends_at_the_watched_steps_last_report_not_before(own_lcm, lcm_url):
    board = lockstep_board.attach(own_lcm, "SIM.LOCKSTEP", FP)
    seen: list[bytes] = []
    own_lcm.subscribe("SIM.LOCKSTEP", lambda c, d: seen.append(d))
    board.put("A", 0)
    board.put("B", 0)
    board.set_limit(2)
    board.set_watch(1)
    pub = lcm.LCM(lcm_url)
    pub.publish("SIM.LOCKSTEP", report("A", 1))
    t0 = time.monotonic()
    assert own_lcm.handle_timeout(300) == 0  # A's report woke only the C loop: B owes step 1
    assert time.monotonic() - t0 >= 0.25
    assert board.last_done("A") == 1 and seen == []
    pub.publish("SIM.LOCKSTEP", report("B", 1))
    t0 = time.monotonic()
    assert own_lcm.handle_timeout(5000) == 1
    assert time.monotonic() - t0 < 4 and board.owing(1) == 0 and seen == []
