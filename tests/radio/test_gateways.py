"""The gateways' handlers at the unit level, on LCM's in-process provider
(memq://): a command crosses byte for byte (a signature appended by the
operator's tool passes), floods of garbage change nothing, the shore's queue
is bounded, and acoustic commands are issued once, only from the shore, only
to their target."""

from __future__ import annotations

import argparse
import os

import lcm

from auv import mission_command_t, modem_rx_t, modem_tx_t, radio_frame_t
from auv import radio_command_status_t as cs
from auvlcm.team_codec import TeamCodec
from tools.radio.outbox import MAX_QUEUE, Outbox
from tools.radio.shore_gateway import ShoreGateway
from tools.radio.shore_gateway import parser as shore_parser
from tools.radio.vehicle_gateway import VehicleGateway
from tools.radio.vehicle_gateway import parser as vehicle_parser
from tools.radio.wire import frame


class Heard:
    def __init__(self, lc: lcm.LCM, pattern: str) -> None:
        self.msgs: list[tuple[str, bytes]] = []
        lc.subscribe(pattern, lambda c, d: self.msgs.append((c, d)))


def drain(lc: lcm.LCM) -> None:
    while lc.handle_timeout(0):
        pass


def vehicle(tmp_path, *extra: str) -> tuple[lcm.LCM, VehicleGateway, argparse.Namespace]:
    lc = lcm.LCM("memq://")
    args = vehicle_parser().parse_args(
        ["--vehicle", "AUV1", "--spool", str(tmp_path / "spool"), "--clock", "system", *extra]
    )
    return lc, VehicleGateway(lc, args), args


def signed_command() -> bytes:
    m = mission_command_t()
    m.vehicle, m.seq, m.command, m.reason = "AUV1", 7, mission_command_t.CMD_PAUSE, "test"
    return m.encode() + b"HMAC" + os.urandom(32)  # fields another branch appends


def test_a_command_crosses_byte_for_byte_and_a_flood_changes_nothing(tmp_path):
    lc, gw, _ = vehicle(tmp_path)
    cmds = Heard(lc, r"AUV1\.(MISSION_CMD|PLUGIN_UPLOAD)")
    sent = Heard(lc, r"RADIO\.TX\.AUV1")
    for i in range(3000):  # garbage frames, chunks of unknown transfers, frames for another node
        f = radio_frame_t()
        f.src, f.dst, f.seq = "SHORE", "AUV1" if i % 3 else "AUV2", i
        f.payload = os.urandom(i % 200) if i % 2 else b""
        f.n_bytes = len(f.payload)
        gw._on_frame("RADIO.RX.AUV1", f)
    box = Outbox("AUV1", chunk_bytes=64, window=10**6)
    box.submit("MISSION_CMD", b"x" * 500, 1, "junk", 0.0).tid = 99
    box.heard(0.0)
    for c in box.due(0.0, 0)[1:]:  # never its first chunk
        gw._on_frame("RADIO.RX.AUV1", decode_frame(frame("SHORE", "AUV1", 1, 0, c.encode())))
    drain(lc)
    assert cmds.msgs == [] and gw.stats["frames_dropped"] == 3000 and gw.asm.refused["unknown transfer"] == 7
    assert not list((tmp_path / "spool").glob("*.part"))
    data = signed_command()
    box = Outbox("AUV1", chunk_bytes=64, window=10**6)
    box.submit("MISSION_CMD", data, 7, "pause", 0.0)
    box.heard(0.0)
    for c in box.due(0.0, 0):
        gw._on_frame("RADIO.RX.AUV1", decode_frame(frame("SHORE", "AUV1", 1, 0, c.encode())))
    drain(lc)
    assert cmds.msgs == [("AUV1.MISSION_CMD", data)]  # as the operator's tool encoded it, signature and all
    assert len(sent.msgs) == 7 + -(-len(data) // 64)  # every chunk is answered, no garbage frame is


def decode_frame(data: bytes) -> radio_frame_t:
    return radio_frame_t.decode(data)


def test_acoustic_commands_run_once_from_the_shore_to_their_target(tmp_path):
    lc, gw, _ = vehicle(tmp_path, "--team-index", "2")
    cmds = Heard(lc, r"AUV1\.MISSION_CMD")
    codec = TeamCodec()

    def hear(origin: int, target: int, kind: int, counter: int) -> None:
        m = modem_rx_t()
        m.vehicle, m.src_vehicle, m.kind = "AUV1", "SHORE", modem_tx_t.KIND_TEAM
        v = dict(origin=origin, target=target, kind=kind, counter=counter, mac_hi=0, mac_lo=0)
        m.payload = codec.encode("command", v)
        m.n_bytes = len(m.payload)
        gw._on_modem("AUV1.MODEM_RX", m)

    hear(15, 2, 1, 500)
    hear(15, 2, 1, 500)  # the repeat
    hear(3, 2, 1, 501)  # not from the shore
    hear(15, 1, 1, 502)  # another vehicle's
    hear(15, 2, 6, 503)  # no such kind
    hear(15, 2, 3, 504)
    drain(lc)
    got = [mission_command_t.decode(d) for _, d in cmds.msgs]
    assert [(m.command, m.seq) for m in got] == [
        (mission_command_t.CMD_ABORT, 500),
        (mission_command_t.CMD_RESUME, 504),
    ]
    assert got[0].manager == "" and "acoustic abort #500" in got[0].reason


def test_the_shore_queue_is_bounded_and_goes_acoustic_only_when_the_radio_is_down():
    lc = lcm.LCM("memq://")
    args = shore_parser().parse_args(["--vehicles", "AUV1", "--clock", "system", "--acoustic", "AUV1=2"])
    gw = ShoreGateway(lc, args)
    status = Heard(lc, r"SHORE\.AUV1\.RADIO_CMD_STATUS")
    modem = Heard(lc, r"SHORE\.MODEM_TX")
    for i in range(MAX_QUEUE + 36):
        gw._on_command("SHORE.AUV1.PLUGIN_UPLOAD", os.urandom(300))
    abort = mission_command_t()
    abort.vehicle, abort.seq, abort.command = "AUV1", (1 << 24) + 9, mission_command_t.CMD_ABORT
    gw._on_command("SHORE.AUV1.MISSION_CMD", abort.encode())  # the radio is down: by the modem
    for _ in range(100):  # a flood of aborts: the modem's queue is bounded, the rest wait for the radio
        gw._on_command("SHORE.AUV1.MISSION_CMD", abort.encode())
    gw.tick()
    drain(lc)
    states = [cs.decode(d) for _, d in status.msgs]
    assert sum(s.state == cs.STATE_QUEUED for s in states) == MAX_QUEUE + 16  # aborts beyond the uploads
    refused = [s for s in states if s.state == cs.STATE_REFUSED]
    assert len(refused) == 36 + 100 - 15 - 16 and "queue full" in refused[0].message
    acoustic = [s for s in states if s.route == "acoustic"]
    assert len(acoustic) == 16 and acoustic[0].state == cs.STATE_IN_FLIGHT and acoustic[0].what == "abort"
    assert len(gw.acoustic) == 48 - 16  # the first frame of each went out now, the repeats 10 s apart
    tx = [modem_tx_t.decode(d) for _, d in modem.msgs]
    assert len(tx) == 16 and tx[0].dst_vehicle == "AUV1"
    v = TeamCodec().decode_frame(bytes(tx[0].payload)).messages[0].values
    assert (v["origin"], v["target"], v["kind"], v["counter"]) == (15, 2, 1, 9)


def test_acoustic_commands_with_team_keys_are_tagged_checked_and_signed(tmp_path):
    """With the team's keys (docs/security.md, "Acoustic"): the shore tags each acoustic
    command, the vehicle's gateway runs a tagged one once and signs what it issues to the
    managers; a stranger's modem (no key, or another key), a frame with one bit changed,
    and a replay are refused and counted; during a rotation the old key still verifies."""
    from auvlcm import auth
    from tools.keys.keygen import main as keygen

    team, stranger = tmp_path / "team.key", tmp_path / "stranger.key"
    assert keygen([str(team)]) == 0 and keygen([str(stranger)]) == 0
    ring, strange = auth.load_keys(team), auth.load_keys(stranger)
    lc = lcm.LCM("memq://")
    sargs = shore_parser().parse_args(["--vehicles", "AUV1", "--clock", "system", "--acoustic", "AUV1=2"])
    sargs.ring = ring
    shore = ShoreGateway(lc, sargs)
    modem = Heard(lc, r"SHORE\.MODEM_TX")
    abort = mission_command_t()
    abort.vehicle, abort.seq, abort.command = "AUV1", 9, mission_command_t.CMD_ABORT
    shore._on_command("SHORE.AUV1.MISSION_CMD", abort.encode())
    shore.tick()
    drain(lc)
    frame_bytes = bytes(modem_tx_t.decode(modem.msgs[0][1]).payload)
    vals = TeamCodec().decode_frame(frame_bytes).messages[0].values
    assert (vals["mac_hi"], vals["mac_lo"]) != (0, 0)

    vargs = vehicle_parser().parse_args(["--vehicle", "AUV1", "--spool", str(tmp_path / "sp"), "--clock", "system"])
    vargs.team_index, vargs.ring = 2, ring
    gw = VehicleGateway(lc, vargs)
    cmds = Heard(lc, r"AUV1\.MISSION_CMD")

    def hear(payload: bytes) -> None:
        m = modem_rx_t()
        m.vehicle, m.src_vehicle, m.kind = "AUV1", "SHORE", modem_tx_t.KIND_TEAM
        m.payload, m.n_bytes = payload, len(payload)
        gw._on_modem("AUV1.MODEM_RX", m)

    codec = TeamCodec()
    forged = dict(vals, counter=vals["counter"] + 1)  # a stranger's frame: a new counter, the old tag
    hear(codec.encode("command", forged))
    untagged = dict(vals, counter=vals["counter"] + 2, mac_hi=0, mac_lo=0)  # a modem with no key
    hear(codec.encode("command", untagged))
    other = dict(vals, counter=vals["counter"] + 3)
    t = auth.acoustic_tag(
        strange.signing.secret, codec.encode("command", dict(other, mac_hi=0, mac_lo=0)), other["counter"]
    )
    hear(codec.encode("command", dict(other, mac_hi=t >> 16, mac_lo=t & 0xFFFF)))  # another team's key
    hear(frame_bytes)  # the shore's: run
    gw.counters.clear()  # a restarted gateway's memory: the window still refuses the copy
    hear(frame_bytes)
    drain(lc)
    assert gw.refused == {"acoustic bad_mac": 3, "acoustic replay": 1}, gw.refused
    assert len(cmds.msgs) == 1
    issued = mission_command_t.decode(cmds.msgs[0][1])
    assert issued.command == mission_command_t.CMD_ABORT and issued.seq == vals["counter"]
    assert auth.Verifier(ring).verify(issued) == auth.OK  # a manager with the key acts on it
    # a rotation: the vehicle holds the old and the new key; a shore not rotated yet still tags with the old
    assert keygen([str(team), "--rotate", "--id", "team-next"]) == 0
    rotated = auth.load_keys(team)
    vargs.ring = rotated
    gw2 = VehicleGateway(lc, vargs)
    tagger_vals = dict(vals, counter=vals["counter"] + 10)
    t = auth.acoustic_tag(
        ring.signing.secret, codec.encode("command", dict(tagger_vals, mac_hi=0, mac_lo=0)), tagger_vals["counter"]
    )
    payload = codec.encode("command", dict(tagger_vals, mac_hi=t >> 16, mac_lo=t & 0xFFFF))
    m = modem_rx_t()
    m.vehicle, m.src_vehicle, m.kind, m.payload, m.n_bytes = (
        "AUV1",
        "SHORE",
        modem_tx_t.KIND_TEAM,
        payload,
        len(payload),
    )
    gw2._on_modem("AUV1.MODEM_RX", m)
    assert rotated.signing.id == "team-next" and gw2.stats["acoustic_commands"] == 1 and gw2.refused == {}
