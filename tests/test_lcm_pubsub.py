"""C and Python processes talk over real udpm (ttl=0), both directions, and the
receive helpers count and drop what fails to decode instead of raising."""

from __future__ import annotations

import math
import random
import subprocess
import time

import lcm
import pytest
from conftest import c_program
from lcm_proc import pump, stop, wait_for_line
from lcm_samples import random_message

from auv import actuators_t, depth_t, nav_solution_t
from auvlcm.rx import Receiver


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_c_publisher_python_subscriber(lcm_url, child_env, sanitized):
    lc = lcm.LCM(lcm_url)
    rx = Receiver(lc)
    navs, depths, acts = [], [], []
    rx.subscribe("AUV7.NAV", nav_solution_t, lambda c, m: navs.append(m), queue_capacity=200)
    rx.subscribe("AUV7.DEPTH", depth_t, lambda c, m: depths.append(m), queue_capacity=200)
    rx.subscribe("AUV7.ACTUATORS", actuators_t, lambda c, m: acts.append(m), queue_capacity=200)
    count, rate = 40, 100.0
    pub = subprocess.Popen(
        [
            c_program("bin/auv-lcm-probe", sanitized),
            "publish-track",
            "--lcm-url",
            lcm_url,
            "--vehicle",
            "AUV7",
            "--count",
            str(count),
            "--rate",
            str(rate),
        ],
        env=child_env,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert pump(lc, lambda: len(acts) == count, timeout=20), f"got {len(navs)}/{len(depths)}/{len(acts)} of {count}"
    assert pub.wait(10) == 0, pub.stderr.read()
    assert [len(navs), len(depths)] == [count, count]
    omega = 1.5 / 50.0
    for i, nav in enumerate(navs):  # the values C computed arrive intact, in order
        t = i / rate
        assert nav.vehicle == "AUV7"
        assert nav.utime == round(t * 1e6)
        assert nav.north_m == pytest.approx(50.0 * math.sin(omega * t), abs=1e-12)
        assert nav.east_m == pytest.approx(50.0 * (1 - math.cos(omega * t)), abs=1e-12)
        assert nav.position_cov_m2[2][2] == pytest.approx(0.25 + 0.001 * i)
        assert depths[i].depth_m == nav.depth_m
        assert acts[i].seq == i and acts[i].prop_rpm == 1500.0
    assert rx.decode_errors == 0


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_python_publisher_c_subscriber_counts_bad_messages(lcm_url, child_env, sanitized):
    listener = subprocess.Popen(
        [
            c_program("bin/auv-lcm-probe", sanitized),
            "listen",
            "--lcm-url",
            lcm_url,
            "--channel",
            "AUV2.NAV",
            "--type",
            "nav_solution_t",
            "--count",
            "4",
            "--timeout-ms",
            "15000",
        ],
        env=child_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        wait_for_line(listener, "ready")
        lc = lcm.LCM(lcm_url)
        rng = random.Random(5)
        good = []
        for i in range(4):
            msg = random_message(nav_solution_t, rng)
            msg.vehicle, msg.utime, msg.north_m = "AUV2", 1000 * i, 10.5 * i
            good.append(msg)
        encoded = good[0].encode()
        bad = [
            depth_t().encode(),  # another type: wrong fingerprint
            encoded[:-3],  # truncated
            b"\x01\x02\x03",  # garbage shorter than a fingerprint
            encoded + b"\x00\x00",
        ]  # trailing bytes: another layout
        for bad_msg, msg in zip(bad, good):  # each bad one before a good one
            lc.publish("AUV2.NAV", bad_msg)
            lc.publish("AUV2.NAV", msg.encode())
            time.sleep(0.02)
        out, err = listener.communicate(timeout=20)
    finally:
        stop(listener)
    assert listener.returncode == 0, err
    lines = out.splitlines()
    values = [ln for ln in lines if ln.startswith("AUV2.NAV ")]
    assert len(values) == 4
    for i, line in enumerate(values):
        assert f"utime={1000 * i} " in line and 'vehicle="AUV2"' in line
        assert f"north_m={10.5 * i:.17g} " in line
    assert lines[-1] == "stats received=8 delivered=4 wrong_fingerprint=2 malformed=2"
    # malformed messages of the type are reported; other types (a pattern
    # matching channels of several types is the normal case) only counted
    assert "truncated or malformed" in err
    assert "wrong fingerprint" not in err


def test_python_receiver_counts_and_drops(lcm_url):
    lc = lcm.LCM(lcm_url)
    rx = Receiver(lc)
    got = []
    sub = rx.subscribe("AUV3.DEPTH", depth_t, lambda c, m: got.append(m))
    msg = depth_t()
    msg.vehicle, msg.depth_m = "AUV3", 12.25
    data = msg.encode()
    for payload in [data, nav_solution_t().encode(), data[:10], data + b"x", b"", data]:
        lc.publish("AUV3.DEPTH", payload)
    assert pump(lc, lambda: sub.stats.received == 6, timeout=5)
    assert [m.depth_m for m in got] == [12.25, 12.25]
    assert (sub.stats.delivered, sub.stats.wrong_fingerprint, sub.stats.malformed) == (2, 2, 2)
    assert rx.decode_errors == 4
    assert "depth_t" in sub.stats.last_error


def test_a_message_its_handler_cannot_use_is_counted_not_fatal(lcm_url, capfd):
    """A value no handler foresaw (here: a depth its handler refuses) is counted with
    the undecodable ones and reported, and lc.handle() goes on (issue 12, item 6)."""
    lc = lcm.LCM(lcm_url)
    rx = Receiver(lc)
    got = []

    def handler(_c, m):
        got.append(1.0 / m.depth_m)  # ZeroDivisionError on a depth of 0

    sub = rx.subscribe("AUV3.DEPTH", depth_t, handler)
    msg = depth_t()
    for depth in (2.0, 0.0, 4.0):
        msg.depth_m = depth
        lc.publish("AUV3.DEPTH", msg.encode())
    assert pump(lc, lambda: sub.stats.received == 3, timeout=5)
    assert got == [0.5, 0.25]
    assert sub.stats.handler_errors == 1 and rx.decode_errors == 1
    assert "ZeroDivisionError" in capfd.readouterr().err
