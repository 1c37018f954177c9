"""auv-radio-vehicle: the vehicle's end of the surface radio (docs/radio.md).

    auv-radio-vehicle --vehicle AUV1 --spool DIR [--clock sim|system] [--team-index N]

Radio in (RADIO.RX.<VEHICLE>): chunks of operator commands. Each is answered
with a radio_ack_t (how far it holds the transfer); a whole whose SHA-256
matches is published, exactly as the shore's tool encoded it, on
<VEHICLE>.MISSION_CMD or <VEHICLE>.PLUGIN_UPLOAD, where the managers check
and acknowledge it as any command. Partial transfers live in --spool (never
in a manager's --plugin-dir), so a restart resumes them.

Radio out (RADIO.TX.<VEHICLE>): at the surface (navigation depth under
--surface-depth-m), every --report-period-s a radio_report_t (position,
mission state, contacts so far, the transfers it holds), and the managers'
answers (<VEHICLE>.MISSION_ACK) heard since the last surfacing.

Acoustic (<VEHICLE>.MODEM_RX, team-link frames): a `command` message from
the shore (origin 15) addressed to --team-index is issued as a
mission_command_t to every manager (abort, pause, resume), once per counter.

Written in Python (docs/radio.md says what a C version on c/drivers/common
would add); the radio is LCM here: at sea a byte pipe would carry the same
frames.
"""

from __future__ import annotations

import argparse
import sys
from collections import deque
from pathlib import Path

import lcm

from auv import (
    chasm_status_t,
    mission_command_t,
    modem_rx_t,
    modem_tx_t,
    nav_solution_t,
    radio_ack_t,
    radio_chunk_t,
    radio_frame_t,
    radio_report_t,
)
from auvlcm import auth, programs
from auvlcm.decode import DecodeError
from auvlcm.rx import Receiver
from auvlcm.team_codec import TeamCodec
from auvlcm.url import check_local, default_url
from tools.radio.acoustic_auth import Checker
from tools.radio.assembler import Assembler
from tools.radio.pipe import BytePipe, run_gateway
from tools.radio.wire import Clock, frame, payload

SHORE = "SHORE"
SHORE_INDEX = 15
ACOUSTIC_KINDS = {
    1: ("abort", mission_command_t.CMD_ABORT),
    2: ("pause", mission_command_t.CMD_PAUSE),
    3: ("resume", mission_command_t.CMD_RESUME),
}
RUN = {0: "LOADING", 1: "RUNNING", 2: "PAUSED", 3: "DONE", 4: "ABORTED", 5: "FAILED"}
MAX_ACKS = 32  # managers' answers kept for the next surfacing
ACK_SENDS = 3  # each sent at this many reports: the radio may lose one


class VehicleGateway:
    def __init__(self, lc: lcm.LCM, args: argparse.Namespace) -> None:
        self.lc, self.v = lc, args.vehicle
        self.clock = Clock(lc, args.clock == "sim")
        self.asm = Assembler(self.v, Path(args.spool), args.idle_expiry_s)
        self.surface_depth_m, self.report_period_s = args.surface_depth_m, args.report_period_s
        self.team_index, self.end_manager = args.team_index, args.end_manager
        self.nav: nav_solution_t | None = None
        self.mission = ""
        self.contacts = 0
        self.acks: deque[list] = deque(maxlen=MAX_ACKS)  # [encoded ack, sends left]
        self.next_report = 0.0
        self.seq = 0
        self.counters: deque[int] = deque(maxlen=16)
        self.codec = TeamCodec()
        # with team keys: acoustic commands checked (acoustic_auth.py) and the commands it
        # issues to the managers signed, so a manager that takes only signed commands acts
        self.ring: auth.KeyRing | None = args.ring
        self.checker = Checker(args.ring) if args.ring is not None else None
        self.refused: dict[str, int] = {}
        self.stats = {"delivered": 0, "acoustic_commands": 0, "frames_dropped": 0}
        rx = self.rx = Receiver(lc)
        v = self.v
        self.pipe = BytePipe(args.tcp, args.device) if args.tcp or args.device else None
        if self.pipe is None:  # the simulated radio; else frames come through the pipe
            rx.subscribe(f"RADIO\\.RX\\.{v}", radio_frame_t, self._on_frame)
        rx.subscribe(f"{v}\\.NAV", nav_solution_t, lambda c, m: setattr(self, "nav", m))
        rx.subscribe(f"{v}\\.CHASM\\.{self.end_manager}", chasm_status_t, self._on_status)
        rx.subscribe(f"{v}\\.MODEM_RX", modem_rx_t, self._on_modem)
        lc.subscribe(f"{v}\\.MISSION_ACK", lambda c, data: self.acks.append([data, ACK_SENDS]))
        lc.subscribe(f"{v}\\.CONTACTS", lambda c, data: setattr(self, "contacts", self.contacts + 1))

    def _send(self, data: bytes) -> None:
        now = self.clock.now() or 0.0
        self.seq += 1
        out = frame(self.v, SHORE, self.seq, int(now * 1e6), data)
        if self.pipe is not None:
            self.pipe.write(out)
        else:
            self.lc.publish(f"RADIO.TX.{self.v}", out)

    def _on_status(self, channel: str, m: chasm_status_t) -> None:
        self.mission = f"{RUN.get(m.run_state, '?')} {'/'.join(m.active_path)}"

    def _on_frame(self, channel: str, f: radio_frame_t) -> None:
        now = self.clock.now()
        try:
            msg = payload(f.payload)
        except DecodeError:
            self.stats["frames_dropped"] += 1
            return
        if now is None or not isinstance(msg, radio_chunk_t) or f.dst != self.v:
            self.stats["frames_dropped"] += 1
            return
        o = self.asm.offer(msg, now)
        if o.data is not None:  # verified whole: handed on exactly as the operator's tool encoded it
            self.lc.publish(f"{self.v}.{o.channel}", o.data)
            self.stats["delivered"] += 1
        ack = radio_ack_t()
        ack.utime, ack.transfer_id, ack.vehicle, ack.next_index = int(now * 1e6), msg.transfer_id, self.v, o.next_index
        ack.state = {"holding": 0, "done": 1, "refused": 2}[o.state]
        ack.reason = o.reason
        self._send(ack.encode())

    def _on_modem(self, channel: str, m: modem_rx_t) -> None:
        if m.kind != modem_tx_t.KIND_TEAM:
            return
        for msg in self.codec.decode_frame(bytes(m.payload)).messages:
            vals = msg.values
            if msg.name != "command" or vals["origin"] != SHORE_INDEX or vals["target"] != self.team_index:
                continue
            if vals["kind"] not in ACOUSTIC_KINDS or vals["counter"] in self.counters:
                continue  # a repeat of one already run, or no command we issue
            if self.checker is not None:
                why = self.checker.check(self.codec, vals)
                if why != auth.OK:  # a stranger's modem, or a frame heard before
                    self.refused[f"acoustic {why}"] = self.refused.get(f"acoustic {why}", 0) + 1
                    continue
            self.counters.append(vals["counter"])
            name, code = ACOUSTIC_KINDS[vals["kind"]]
            cmd = mission_command_t()
            now = self.clock.now() or m.utime * 1e-6
            cmd.utime, cmd.vehicle, cmd.manager, cmd.seq, cmd.command = (
                int(now * 1e6),
                self.v,
                "",
                vals["counter"],
                code,
            )
            cmd.plan_name, cmd.plan_text, cmd.reason = "", "", f"shore, acoustic {name} #{vals['counter']}"
            if self.ring is not None:
                auth.sign(cmd, self.ring, f"auv-radio-vehicle {self.v}")
            self.lc.publish(f"{self.v}.MISSION_CMD", cmd.encode())
            self.stats["acoustic_commands"] += 1

    def at_surface(self) -> bool:
        return self.nav is not None and self.nav.depth_m < self.surface_depth_m

    def tick(self) -> None:
        now = self.clock.now()
        if now is None:
            return
        self.asm.expire(now)
        if now < self.next_report or not self.at_surface():
            return
        self.next_report = now + self.report_period_s
        self._send(self.report(now).encode())
        for a in list(self.acks):
            self._send(a[0])
            a[1] -= 1
            if a[1] <= 0:
                self.acks.remove(a)

    def report(self, now: float) -> radio_report_t:
        r = radio_report_t()
        r.utime, r.vehicle, r.mission, r.contacts = int(now * 1e6), self.v, self.mission, self.contacts
        n = self.nav
        if n is not None:
            r.latitude_deg, r.longitude_deg, r.north_m, r.east_m = n.latitude_deg, n.longitude_deg, n.north_m, n.east_m
            r.depth_m, r.nav_status, r.nav_utime = n.depth_m, n.status, n.utime
        held = self.asm.holding()
        r.n_transfers, r.transfer_id, r.next_index = len(held), [t for t, _ in held], [i for _, i in held]
        r.refused = sum(self.asm.refused.values()) + sum(self.refused.values())
        return r

    def summary(self) -> str:
        every = {**self.asm.refused, **self.refused}
        refused = ", ".join(f"{k} {n}" for k, n in sorted(every.items())) or "none"
        s = self.stats
        pipe = f", pipe dropped {dict(self.pipe.deframer.dropped)}" if self.pipe is not None else ""
        return (
            f"auv-radio-vehicle {self.v}: delivered {s['delivered']}, acoustic commands "
            f"{s['acoustic_commands']}, frames dropped {s['frames_dropped']}, refused: {refused}{pipe}"
        )


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="auv-radio-vehicle", description=__doc__.split("\n\n")[0])
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)", default=None)
    ap.add_argument("--vehicle", required=True)
    ap.add_argument("--spool", required=True, help="folder for partial transfers (not the plugin dir)")
    ap.add_argument("--clock", choices=("sim", "system"), default="sim")
    ap.add_argument("--team-index", type=int, default=-1, help="this vehicle's team index for acoustic commands")
    ap.add_argument("--end-manager", default="NAVIGATOR", help="the manager whose state is reported home")
    ap.add_argument("--surface-depth-m", type=float, default=0.5, help="at the surface above this nav depth")
    ap.add_argument("--report-period-s", type=float, default=2.0)
    pipe = ap.add_mutually_exclusive_group()
    pipe.add_argument("--tcp", default="", metavar="HOST:PORT", help="a real radio's TCP port (docs/radio.md)")
    pipe.add_argument("--device", default="", metavar="PATH", help="a real radio's serial device")
    ap.add_argument("--idle-expiry-s", type=float, default=3600.0, help="drop a partial transfer idle this long")
    auth.add_key_file_argument(ap)
    ap.set_defaults(ring=None)  # main() loads the key file into it
    return ap


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        url = check_local(args.url or default_url())
        args.ring = auth.ring_for(args.key_file, "auv-radio-vehicle")
    except (ValueError, auth.KeyFileError) as exc:
        print(f"auv-radio-vehicle: {exc}", file=sys.stderr)
        return 2
    gw = run_gateway("auv-radio-vehicle", url, lambda lc: VehicleGateway(lc, args))
    print(gw.summary(), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
