"""The modem's parts in-process: loss curve, seeded draws, size and rate
limits, propagation timing and range limit, peer-report codec, config errors."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from auv import acoustic_frame_t, modem_status_t, modem_tx_t, peer_report_t
from sim.config import ConfigError, loads
from sim.environment import Environment, EnvParams
from sim.modem.acoustics import frame_duration_s, loss_probability, snr_db, uniform_draw
from sim.modem.config import ModemConfig
from sim.modem.peers import heard_report, report_frame
from sim.modem.receiver import Receiver
from sim.modem.transmitter import Transmitter

DT = 0.02


def tx_msg(n=10, seq=1, dst="", vehicle="AUV1", kind=modem_tx_t.KIND_RAW) -> modem_tx_t:
    m = modem_tx_t()
    m.vehicle, m.dst_vehicle, m.seq, m.kind = vehicle, dst, seq, kind
    m.n_bytes, m.payload = n, bytes(i % 256 for i in range(n))
    return m


def frame(src="AUV1", seq=1, t0=0.0, pos=(0.0, 0.0, 10.0), dst="") -> acoustic_frame_t:
    f = acoustic_frame_t()
    f.utime = int(round(t0 * 1e6))
    f.tx_north_m, f.tx_east_m, f.tx_depth_m = pos
    f.source_level_db = 185.0
    f.src_vehicle, f.dst_vehicle, f.seq, f.kind = src, dst, seq, modem_tx_t.KIND_RAW
    f.n_bytes, f.payload = 3, b"abc"
    return f


def receiver(cfg=None, env=None, vehicle="AUV2", seed=7):
    env = env or Environment(EnvParams(sound_speed_mps=1500.0))
    return Receiver(cfg or ModemConfig(), vehicle, seed, env, modem_status_t())


def run_until_arrival(rx, pos, t_end=5.0):
    t = 0.0
    while t < t_end:
        t = round(t + DT, 9)
        got = rx.step(t, pos)
        if got or not rx.pending:
            return t, got
    return t, []


# ------------------------------------------------------------------ curve
def test_loss_curve_endpoints_shape_and_range_limit():
    cfg = ModemConfig(max_range_m=2000, loss_at_zero=0.1, loss_at_max_range=0.6, loss_exponent=2)
    assert loss_probability(0.0, cfg) == pytest.approx(0.1)
    assert loss_probability(1000.0, cfg) == pytest.approx(0.1 + 0.5 * 0.25)
    assert loss_probability(2000.0, cfg) == pytest.approx(0.6)
    assert loss_probability(2000.1, cfg) == 1.0
    ps = [loss_probability(r, cfg) for r in range(0, 2001, 100)]
    assert all(b >= a for a, b in zip(ps, ps[1:]))


def test_draws_are_uniform_deterministic_and_independent_per_receiver():
    draws = [uniform_draw(42, "AUV1", s, s * 1000, "AUV2") for s in range(20000)]
    assert draws == [uniform_draw(42, "AUV1", s, s * 1000, "AUV2") for s in range(20000)]
    assert all(0.0 <= u < 1.0 for u in draws)
    assert abs(sum(draws) / len(draws) - 0.5) < 0.01
    assert sum(u < 0.1 for u in draws) == pytest.approx(2000, abs=4 * math.sqrt(20000 * 0.09))
    other = [uniform_draw(42, "AUV1", s, s * 1000, "AUV3") for s in range(20000)]
    both_low = sum(a < 0.5 and b < 0.5 for a, b in zip(draws, other))
    assert both_low == pytest.approx(5000, abs=4 * math.sqrt(20000 * 0.25 * 0.75))
    reseeded = [uniform_draw(43, "AUV1", s, s * 1000, "AUV2") for s in range(100)]
    assert reseeded != draws[:100]


def test_snr_falls_with_range():
    cfg = ModemConfig()
    assert snr_db(1.0, 185.0, cfg) == pytest.approx(135.0 - 0.001)  # 1 dB/km
    assert snr_db(1000.0, 185.0, cfg) == pytest.approx(185 - 60 - 1 - 50)
    assert snr_db(2000.0, 185.0, cfg) < snr_db(1000.0, 185.0, cfg)


# ----------------------------------------------------------- transmitter
def test_size_limit_refuses_with_reason_and_counts():
    st = modem_status_t()
    tx = Transmitter(ModemConfig(max_frame_bytes=32), "AUV1", st)
    assert isinstance(tx.send(0.0, (0, 0, 0), tx_msg(32, seq=1)), acoustic_frame_t)
    out = tx.send(100.0, (0, 0, 0), tx_msg(33, seq=2))
    assert out == "33 bytes is over max_frame_bytes = 32"
    assert (st.sent, st.refused_size, st.last_refused_seq, st.last_refusal) == (1, 1, 2, out)


def test_rate_limit_is_the_frame_duration_then_min_interval():
    cfg = ModemConfig(bitrate_bps=800, frame_overhead_s=0.5)
    st = modem_status_t()
    tx = Transmitter(cfg, "AUV1", st)
    dur = frame_duration_s(100, cfg)
    assert dur == pytest.approx(0.5 + 1.0)
    assert isinstance(tx.send(10.0, (0, 0, 0), tx_msg(100, seq=1)), acoustic_frame_t)
    reason = tx.send(10.0 + dur - 0.01, (0, 0, 0), tx_msg(5, seq=2))
    assert reason.startswith("busy: frame 1 is on the air until t = 11.500 s")
    assert isinstance(tx.send(10.0 + dur, (0, 0, 0), tx_msg(5, seq=3)), acoustic_frame_t)
    assert (st.sent, st.refused_rate) == (2, 1)
    assert st.busy_until_utime == int(round((11.5 + frame_duration_s(5, cfg)) * 1e6))

    st2 = modem_status_t()
    tx2 = Transmitter(ModemConfig(min_interval_s=10.0), "AUV1", st2)
    tx2.send(0.0, (0, 0, 0), tx_msg(5, seq=1))
    assert "min_interval_s = 10" in tx2.send(9.0, (0, 0, 0), tx_msg(5, seq=2))
    assert isinstance(tx2.send(10.0, (0, 0, 0), tx_msg(5, seq=3)), acoustic_frame_t)


@pytest.mark.parametrize(
    "msg, reason",
    [
        (tx_msg(5, vehicle="AUV9"), "vehicle 'AUV9' is not this modem's vehicle 'AUV1'"),
        (tx_msg(5, kind=7), "unknown kind 7"),
        (tx_msg(5, dst="AUV1"), "addressed to itself"),
        (tx_msg(0), "empty frame"),
    ],
)
def test_invalid_frames_are_refused(msg, reason):
    st = modem_status_t()
    assert Transmitter(ModemConfig(), "AUV1", st).send(0.0, (0, 0, 0), msg) == reason
    assert (st.refused_invalid, st.sent) == (1, 0)


def test_accepted_frame_carries_true_position_and_send_time():
    tx = Transmitter(ModemConfig(), "AUV1", modem_status_t())
    f = tx.send(12.34, (1.0, 2.0, 3.0), tx_msg(4, seq=9, dst="AUV2", vehicle=""))
    assert (f.utime, f.tx_north_m, f.tx_east_m, f.tx_depth_m) == (12_340_000, 1.0, 2.0, 3.0)
    assert (f.src_vehicle, f.dst_vehicle, f.seq, f.payload) == ("AUV1", "AUV2", 9, bytes(range(4)))


# -------------------------------------------------------------- receiver
@pytest.mark.parametrize("gradient", [0.0, 0.05])
def test_arrival_is_distance_over_sound_speed_within_one_step(gradient):
    env = Environment(EnvParams(sound_speed_mps=1490.0, sound_speed_gradient_per_m=gradient))
    cfg = ModemConfig(loss_at_zero=0.0, loss_at_max_range=0.0)
    rx = receiver(cfg, env)
    pos = (600.0, 800.0, 30.0)  # 1000.2 m from (0, 0, 10)
    rx.hear(frame(t0=0.0))
    t, got = run_until_arrival(rx, pos)
    d = math.dist((0.0, 0.0, 10.0), pos)
    c = 1490.0 + gradient * 20.0
    assert len(got) == 1
    assert got[0].utime == int(round(d / c * 1e6))
    assert t - DT < d / c <= t + 1e-9
    assert got[0].range_m == pytest.approx(d) and got[0].tx_utime == 0 and got[0].vehicle == "AUV2"


def test_moving_receiver_meets_the_wavefront():
    """A receiver closing at 3 m/s hears the frame when the sphere reaches it."""
    cfg = ModemConfig(loss_at_zero=0.0, loss_at_max_range=0.0)
    rx = receiver(cfg)
    rx.hear(frame(t0=0.0, pos=(0.0, 0.0, 0.0)))
    t = 0.0
    while True:
        t = round(t + DT, 9)
        pos = (1500.0 - 3.0 * t, 0.0, 0.0)
        got = rx.step(t, pos)
        if got:
            break
    exact = 1500.0 / 1503.0  # 1500 t = 1500 - 3 t
    assert t - DT < exact <= t
    assert abs(got[0].utime / 1e6 - exact) < 3.0 * DT / 1500.0 + 1e-6


def test_out_of_range_frames_never_arrive():
    cfg = ModemConfig(max_range_m=1000.0, loss_at_zero=0.0, loss_at_max_range=0.0)
    st = modem_status_t()
    rx = Receiver(cfg, "AUV2", 1, Environment(EnvParams()), st)
    for seq in range(50):
        rx.hear(frame(seq=seq, t0=seq * 0.1))
    t, got = 0.0, []
    for _ in range(1000):
        t = round(t + DT, 9)
        got += rx.step(t, (1000.5, 0.0, 10.0))
    assert got == [] and rx.pending == [] and st.out_of_range == 50 and st.received == 0


def test_own_frames_and_frames_for_others_are_ignored():
    rx = receiver(vehicle="AUV2")
    rx.hear(frame(src="AUV2"))
    rx.hear(frame(dst="AUV3"))
    rx.hear(frame(src="not a vehicle"))
    assert rx.pending == [] and rx.bad_frames == 1
    rx.hear(frame(dst="AUV2"))
    assert len(rx.pending) == 1


@pytest.mark.parametrize("range_m", [100.0, 1000.0, 1800.0])
def test_loss_rate_follows_the_curve(range_m):
    cfg = ModemConfig(max_range_m=2000, loss_at_zero=0.05, loss_at_max_range=0.6)
    st = modem_status_t()
    rx = Receiver(cfg, "AUV2", 11, Environment(EnvParams()), st)
    n = 4000
    for seq in range(n):
        rx.hear(frame(seq=seq, t0=0.0, pos=(0.0, 0.0, 0.0)))
    rx.step(10.0, (range_m, 0.0, 0.0))
    p = loss_probability(range_m, cfg)
    sigma = math.sqrt(n * p * (1 - p))
    assert st.lost + st.received == n
    assert abs(st.lost - n * p) < 4.0 * sigma, (st.lost, n * p, sigma)


def test_losses_repeat_exactly_with_the_same_seed():
    def lost_seqs(seed):
        rx = receiver(ModemConfig(loss_at_zero=0.3, loss_at_max_range=0.3), seed=seed)
        for seq in range(300):
            rx.hear(frame(seq=seq))
        return {m.seq for m in rx.step(10.0, (500.0, 0.0, 10.0))}

    assert lost_seqs(5) == lost_seqs(5)
    assert lost_seqs(5) != lost_seqs(6)


# ----------------------------------------------------------- peer reports
def test_report_round_trip_through_a_frame():
    r = peer_report_t()
    r.utime, r.vehicle, r.seq, r.north_m, r.active_state = 5_000_000, "AUV1", 4, 12.5, "mission/survey"
    m = report_frame(r, "AUV1")
    assert m.kind == modem_tx_t.KIND_NAV_REPORT and m.seq == 4 and m.dst_vehicle == ""
    assert m.n_bytes == len(m.payload) < ModemConfig().max_frame_bytes
    f = Transmitter(ModemConfig(), "AUV1", modem_status_t()).send(5.0, (0, 0, 0), m)
    rx = receiver(ModemConfig(loss_at_zero=0.0, loss_at_max_range=0.0))
    rx.hear(f)
    (got,) = rx.step(6.0, (10.0, 0.0, 0.0))
    heard = heard_report(got)
    assert (heard.vehicle, heard.heard_by, heard.seq, heard.north_m) == ("AUV1", "AUV2", 4, 12.5)
    assert heard.utime == 5_000_000 and heard.active_state == "mission/survey"


def test_a_report_that_lies_about_its_sender_is_refused():
    from auvlcm.decode import DecodeError

    r = peer_report_t()
    r.vehicle = "AUV3"
    f = frame(src="AUV1")
    f.kind, f.payload = modem_tx_t.KIND_NAV_REPORT, r.encode()
    f.n_bytes = len(f.payload)
    rx = receiver(ModemConfig(loss_at_zero=0.0, loss_at_max_range=0.0))
    rx.hear(f)
    (got,) = rx.step(6.0, (10.0, 0.0, 0.0))
    with pytest.raises(DecodeError, match="describes 'AUV3' but was sent by 'AUV1'"):
        heard_report(got)
    got.payload = got.payload[:-2]
    with pytest.raises(DecodeError):
        heard_report(got)


# ----------------------------------------------------------------- config
def test_no_section_no_modem_and_defaults_take_the_world_seed():
    assert loads("environment: {seed: 3}\n").modem is None
    cfg = loads("environment: {seed: 3}\nmodem: {}\n").modem
    assert cfg == ModemConfig(seed=3)
    assert loads("modem: {enabled: false, seed: 9}\n").modem.seed == 9


def test_config_errors_name_line_column_and_key():
    text = (
        "modem:\n"
        "  max_frame_bytes: 0\n"
        "  loss_at_zero: 1.5\n"
        "  bitrate_bps: -3\n"
        "  max_range: 100\n"
        "  peer_reports: maybe\n"
    )
    with pytest.raises(ConfigError) as exc:
        loads(text, Path("m.yaml"))
    errs = exc.value.errors
    assert "m.yaml:2:20: modem.max_frame_bytes: must be in [1, 32767]" in errs
    assert "m.yaml:3:17: modem.loss_at_zero: must be in [0, 1]" in errs
    assert "m.yaml:4:16: modem.bitrate_bps: must be > 0" in errs
    assert any(e.startswith("m.yaml:5:3: modem.max_range: unknown key; did you mean 'max_range_m'") for e in errs)
    assert any(e.startswith("m.yaml:6:17: modem.peer_reports: expected true/false") for e in errs)
    assert len(errs) == 5
