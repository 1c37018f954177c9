"""auv-radio-shore: the shore's end of the surface radio (docs/radio.md).

    auv-radio-shore --vehicles AUV1,AUV2 [--clock sim|system] [--acoustic AUV1=0,AUV2=1]

The operator's tools publish on the shore's side of the radio:
SHORE.<VEHICLE>.MISSION_CMD and SHORE.<VEHICLE>.PLUGIN_UPLOAD (auvctl --shore).
Each message is queued as it is, opaque bytes (only its seq and kind are read,
for the operator's display: a signature appended to it passes untouched),
and sent over the radio in chunks while the vehicle is heard
(tools/radio/outbox.py). While the radio is down, an abort, pause or resume
goes through the shore's acoustic modem instead (SHORE.MODEM_TX, a team-link
`command`, sent --acoustic-repeats times) to a vehicle with a team index in
--acoustic; a plan or a plugin never does.

Out: SHORE.<VEHICLE>.RADIO_CMD_STATUS (every change of every command: queued,
in flight, delivered, acknowledged, expired, refused), SHORE.<VEHICLE>.MISSION_ACK
(the managers' answers, as they were published on the vehicle),
SHORE.<VEHICLE>.RADIO_REPORT (the vehicle's status home).
"""

from __future__ import annotations

import argparse
import sys

import lcm

from auv import (
    mission_ack_t,
    mission_command_t,
    modem_tx_t,
    plugin_upload_t,
    radio_ack_t,
    radio_frame_t,
    radio_report_t,
)
from auv import (
    radio_command_status_t as cs,
)
from auvlcm import auth, programs
from auvlcm.decode import DecodeError, decode_strict
from auvlcm.rx import Receiver
from auvlcm.team_codec import TeamCodec
from auvlcm.url import check_local, default_url
from tools.console.mission_commands import COMMANDS
from tools.radio.acoustic_auth import Tagger
from tools.radio.outbox import MAX_QUEUE, MAX_URGENT, Outbox, Transfer
from tools.radio.pipe import BytePipe, run_gateway
from tools.radio.wire import MAX_BYTES, Clock, frame, payload

SHORE = "SHORE"
SHORE_INDEX = 15
NAMES = {code: name for name, code in COMMANDS.items()}
ACOUSTIC = {mission_command_t.CMD_ABORT: 1, mission_command_t.CMD_PAUSE: 2, mission_command_t.CMD_RESUME: 3}
COUNTER_MASK = (1 << 24) - 1
MAX_ACOUSTIC_FRAMES = 48  # waiting for the shore's modem, repeats included


def describe(channel: str, data: bytes) -> tuple[int, str, int]:
    """(seq, what, command code or -1) read from a command, without changing it."""
    try:
        if channel == "MISSION_CMD":
            m = decode_strict(mission_command_t, data)
            what = NAMES.get(m.command, f"command {m.command}")
            return m.seq, what + (f" {m.plan_name}" if m.plan_name else ""), m.command
        u = decode_strict(plugin_upload_t, data)
        return u.seq, f"upload {u.plugin_name} {u.plugin_version}", -1
    except DecodeError:
        return -1, "unreadable", -1


class ShoreGateway:
    def __init__(self, lc: lcm.LCM, args: argparse.Namespace) -> None:
        self.lc = lc
        self.clock = Clock(lc, args.clock == "sim")
        self.vehicles = [v for v in args.vehicles.split(",") if v]
        self.boxes = {
            v: Outbox(v, args.chunk_bytes, args.window, args.retry_s, args.link_timeout_s, args.expiry_s)
            for v in self.vehicles
        }
        self.team = dict((k, int(i)) for k, i in (p.split("=") for p in args.acoustic.split(",") if p))
        self.repeats, self.acoustic_interval_s = args.acoustic_repeats, args.acoustic_interval_s
        self.acoustic: list[tuple[float, bytes, str]] = []  # (when, team frame, vehicle)
        self.seq = 0
        self.codec = TeamCodec()
        self.tagger = Tagger(args.ring) if args.ring is not None else None  # acoustic tags (acoustic_auth.py)
        self.dropped = 0
        self.pending: list[tuple[str, bytes]] = []
        vs = "|".join(self.vehicles)
        lc.subscribe(f"SHORE\\.({vs})\\.(MISSION_CMD|PLUGIN_UPLOAD)", self._on_command)
        self.pipe = BytePipe(args.tcp, args.device) if args.tcp or args.device else None
        if self.pipe is None:  # the simulated radio; else frames come through the pipe
            Receiver(lc).subscribe("RADIO\\.RX\\.SHORE", radio_frame_t, self._on_frame)

    def _on_command(self, channel: str, data: bytes) -> None:
        now = self.clock.now()
        if now is None and len(self.pending) < MAX_QUEUE:  # before the world's first clock: held until it
            self.pending.append((channel, data))
            return
        _, v, suffix = channel.split(".")
        box = self.boxes[v]
        seq, what, code = describe(suffix, data)
        t0 = now if now is not None else 0.0
        acoustic_room = len(self.acoustic) < MAX_ACOUSTIC_FRAMES  # else by radio, at the next surfacing
        if now is not None and code in ACOUSTIC and not box.link_up(now) and v in self.team and acoustic_room:
            # the counter: with keys, the tagger's (it only grows); else the command's own seq
            counter = self.tagger.counter() if self.tagger else seq & COUNTER_MASK or 1
            t = Transfer(counter, v, suffix, data, seq, what, now, box.expiry_s, box.chunk_bytes)
            t.route = "acoustic"
            t.set(cs.STATE_IN_FLIGHT)
            box.finished.append(t)
            msg = dict(origin=SHORE_INDEX, target=self.team[v], kind=ACOUSTIC[code], counter=t.tid, mac_hi=0, mac_lo=0)
            if self.tagger:
                msg = self.tagger.tag(self.codec, msg)
            body = self.codec.encode("command", msg)
            self.acoustic += [(now + i * self.acoustic_interval_s, body, v) for i in range(self.repeats)]
            return
        full = len(box.queue) >= (MAX_QUEUE + MAX_URGENT if code in ACOUSTIC else MAX_QUEUE)
        if len(data) > MAX_BYTES or full or now is None:
            t = Transfer(0, v, suffix, b"", seq, what, t0, 0.0, 1)
            why = "no clock yet" if now is None else ("too large" if len(data) > MAX_BYTES else "queue full")
            t.set(cs.STATE_REFUSED, f"refused at the shore: {why}")
            self.lc.publish(f"SHORE.{v}.RADIO_CMD_STATUS", t.status(int(t0 * 1e6)).encode())  # kept nowhere
            return
        # abort, pause and resume go before any plan or plugin still waiting
        box.submit(suffix, data, seq, what, now, urgent=code in ACOUSTIC)

    def _on_frame(self, channel: str, f: radio_frame_t) -> None:
        now = self.clock.now()
        box = self.boxes.get(f.src)
        try:
            msg = payload(f.payload)
        except DecodeError:
            msg = None
        if box is None or now is None or msg is None or f.dst != SHORE:
            self.dropped += 1
            return
        if isinstance(msg, radio_ack_t):
            box.on_ack(msg, now)
        elif isinstance(msg, radio_report_t):
            box.heard(now, dict(zip(msg.transfer_id, msg.next_index)))
            self.lc.publish(f"SHORE.{f.src}.RADIO_REPORT", bytes(f.payload))
        elif isinstance(msg, mission_ack_t):
            box.heard(now)
            self.lc.publish(f"SHORE.{f.src}.MISSION_ACK", bytes(f.payload))
            text = f"{msg.manager} {('ok', 'rejected', 'failed')[msg.result % 3]}: {msg.message}"
            box.on_manager_ack(msg.seq, text)
            self._acoustic_ack(box, msg.seq, text)

    def _acoustic_ack(self, box: Outbox, seq: int, text: str) -> None:
        for t in box.finished:
            if t.route == "acoustic" and t.tid == (seq & COUNTER_MASK) and t.state == cs.STATE_IN_FLIGHT:
                t.set(cs.STATE_ACKNOWLEDGED, text)

    def tick(self) -> None:
        now = self.clock.now()
        if now is None:
            return
        us = int(now * 1e6)
        for channel, data in self.pending:
            self._on_command(channel, data)
        self.pending.clear()
        for v, box in self.boxes.items():
            for c in box.due(now, us):
                self.seq += 1
                out = frame(SHORE, v, self.seq, us, c.encode())
                if self.pipe is not None:
                    self.pipe.write(out)
                else:
                    self.lc.publish("RADIO.TX.SHORE", out)
            for t in box.finished:
                if t.route == "acoustic" and t.state == cs.STATE_IN_FLIGHT and now - t.created_s > t.expiry_s:
                    t.set(cs.STATE_EXPIRED, "no answer heard")
            for s in box.statuses(us):
                self.lc.publish(f"SHORE.{v}.RADIO_CMD_STATUS", s.encode())
        for item in [a for a in self.acoustic if a[0] <= now]:
            self.acoustic.remove(item)
            m = modem_tx_t()
            self.seq += 1
            m.utime, m.vehicle, m.dst_vehicle, m.seq, m.kind = us, SHORE, item[2], self.seq, modem_tx_t.KIND_TEAM
            m.n_bytes, m.payload = len(item[1]), item[1]
            self.lc.publish("SHORE.MODEM_TX", m.encode())


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="auv-radio-shore", description=__doc__.split("\n\n")[0])
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)", default=None)
    ap.add_argument("--vehicles", required=True, help="comma-separated vehicle ids")
    ap.add_argument("--clock", choices=("sim", "system"), default="sim")
    ap.add_argument("--chunk-bytes", type=int, default=512)
    ap.add_argument("--window", type=int, default=8, help="chunks sent beyond the last acknowledged")
    ap.add_argument("--retry-s", type=float, default=2.0, help="resend from the last acknowledged after this")
    ap.add_argument("--link-timeout-s", type=float, default=5.0, help="the link is down after this long unheard")
    ap.add_argument("--expiry-s", type=float, default=3600.0, help="a command not delivered by then expires")
    ap.add_argument("--acoustic", default="", help="team indices for acoustic commands: AUV1=0,AUV2=1")
    pipe = ap.add_mutually_exclusive_group()
    pipe.add_argument("--tcp", default="", metavar="HOST:PORT", help="a real radio's TCP port (docs/radio.md)")
    pipe.add_argument("--device", default="", metavar="PATH", help="a real radio's serial device")
    ap.add_argument("--acoustic-repeats", type=int, default=3)
    ap.add_argument("--acoustic-interval-s", type=float, default=10.0)
    auth.add_key_file_argument(ap)
    ap.set_defaults(ring=None)  # main() loads the key file into it
    return ap


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        url = check_local(args.url or default_url())
        if not 64 <= args.chunk_bytes <= 4096:
            raise ValueError("--chunk-bytes must be 64 .. 4096")
        # the team keys: acoustic commands are tagged with the newest (radio ones travel as signed)
        args.ring = auth.ring_for(args.key_file, "auv-radio-shore")
    except (ValueError, auth.KeyFileError) as exc:
        print(f"auv-radio-shore: {exc}", file=sys.stderr)
        return 2
    gw = run_gateway("auv-radio-shore", url, lambda lc: ShoreGateway(lc, args))
    pipe = f", pipe dropped {dict(gw.pipe.deframer.dropped)}" if gw.pipe is not None else ""
    print(f"auv-radio-shore: frames dropped {gw.dropped}{pipe}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
