"""The shore gateway's handlers at the unit level, on LCM's in-process
provider (memq://): the shore's queue is bounded and goes acoustic only when
the radio is down. The vehicle's gateway is auv-radio (c/drivers/radio): its
tests are tests/drivers/test_radio.c and tests/radio/test_radio_driver.py."""

from __future__ import annotations

import os

import lcm

from auv import mission_command_t, modem_tx_t
from auv import radio_command_status_t as cs
from auvlcm.team_codec import TeamCodec
from tools.radio.outbox import MAX_QUEUE
from tools.radio.shore_gateway import ShoreGateway
from tools.radio.shore_gateway import parser as shore_parser


class Heard:
    def __init__(self, lc: lcm.LCM, pattern: str) -> None:
        self.msgs: list[tuple[str, bytes]] = []
        lc.subscribe(pattern, lambda c, d: self.msgs.append((c, d)))


def drain(lc: lcm.LCM) -> None:
    while lc.handle_timeout(0):
        pass


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
