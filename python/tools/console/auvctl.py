#!/usr/bin/env python3
"""The operator's command line: command a vehicle's managers, read its status.

    auvctl pause|resume|abort|stop VEHICLE [--manager NAME] [--reason TEXT]
    auvctl load VEHICLE PLAN.chasm [--manager NAME]
    auvctl upload VEHICLE PLUGIN.so [--manager NAME] [--name NAME] [--version V]
    auvctl status VEHICLE [--manager NAME] [--json]

Commands go over <VEHICLE>.MISSION_CMD (uploads over <VEHICLE>.PLUGIN_UPLOAD)
and wait for every addressed manager's acknowledgement on <VEHICLE>.MISSION_ACK:
one line per ack, "VEHICLE MANAGER ok|rejected|failed: message". Without
--manager every manager of the vehicle is addressed; those heard on
<VEHICLE>.CHASM.* while waiting are the ones expected to answer.

With --shore the command goes to the radio's shore gateway instead
(SHORE.<VEHICLE>.MISSION_CMD, SHORE.<VEHICLE>.PLUGIN_UPLOAD; docs/radio.md): each
change of its state is printed ("AUV1 upload survey 1 (radio): in flight 40%"),
the last one, acknowledged, with the managers' answers, once the vehicle
surfaced and sent them home (give --timeout accordingly). An expired or
refused command, or an answer that is not ok, exits 1.

Exit status: 0 every ack ok (status: the vehicle was heard); 1 a manager
rejected or failed the command; 2 usage or file error; 3 no answer within
--timeout (nothing heard from the vehicle).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import lcm

from auvlcm import auth, programs
from auvlcm.url import check_local, default_url
from tools.console import mission_commands as mc
from tools.console.model import Model
from tools.console.radio_view import STATES
from tools.console.sources import decode

SETTLE_S = 0.5  # after the last expected ack, wait this long for stragglers


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="auvctl", description=__doc__.split("\n\n")[0])
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)", default=None)
    ap.add_argument("--timeout", type=float, default=5.0, help="seconds to wait for answers (default 5)")
    ap.add_argument("--shore", action="store_true", help="send through the radio's shore gateway (docs/radio.md)")
    auth.add_key_file_argument(ap)
    sub = ap.add_subparsers(dest="cmd", required=True, metavar="COMMAND")
    for name in ("pause", "resume", "abort", "stop"):
        p = sub.add_parser(name, help=f"{name} the mission")
        p.add_argument("vehicle")
        p.add_argument("--reason", default="")
    p = sub.add_parser("load", help="replace the plan with PLAN.chasm")
    p.add_argument("vehicle")
    p.add_argument("plan", type=Path)
    p = sub.add_parser("upload", help="send a behavior plugin (.so) to hot-load")
    p.add_argument("vehicle")
    p.add_argument("plugin", type=Path)
    p.add_argument("--name", default="", help="plugin name (default: from the file name, chasm_NAME.so)")
    p.add_argument("--version", default="1")
    p = sub.add_parser("status", help="print the vehicle's managers, navigation and modem")
    p.add_argument("vehicle")
    p.add_argument("--json", action="store_true", help="print the status as JSON")
    for p in sub.choices.values():
        p.add_argument("--manager", default="", help="one manager (default: every manager)")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    try:
        url = check_local(args.url or default_url())
        ring = auth.ring_for(args.key_file, "auvctl") if args.cmd != "status" else None
        if args.cmd == "load":
            plan_text = args.plan.read_text()
            if len(plan_text.encode()) > mc.MAX_PLAN_BYTES:
                raise ValueError(
                    f"{args.plan}: {len(plan_text.encode())} bytes, the managers take plans "
                    f"of at most {mc.MAX_PLAN_BYTES} bytes"
                )
        if args.cmd == "upload" and not args.plugin.is_file():
            raise OSError(f"{args.plugin}: no such file")
    except (OSError, ValueError, UnicodeDecodeError) as exc:  # KeyFileError is a ValueError
        print(f"auvctl: {exc}", file=sys.stderr)
        return 2
    lc = lcm.LCM(url)
    model = Model()
    vid = args.vehicle

    def on_raw(channel: str, data: bytes) -> None:
        msg = decode(data)
        if msg is not None and getattr(msg, "vehicle", vid) == vid:
            model.apply(channel, msg)

    lc.subscribe(rf"{vid}\.(CHASM\.[A-Za-z0-9_]+|MISSION_ACK|NAV|NAV_STATUS|TRUTH|MODEM_STATUS)", on_raw)
    if args.cmd == "status":
        return _status(lc, model, vid, args)

    seq = mc.first_seq()
    prefix = "SHORE." if args.shore else ""
    radio = RadioProgress(lc, vid, seq) if args.shore else None
    if args.cmd == "upload":
        msg = mc.upload(vid, args.manager, args.plugin, seq, args.version, args.name)
        if ring:
            auth.sign(msg, ring, auth.default_sender("auvctl"))
        lc.publish(f"{prefix}{vid}.PLUGIN_UPLOAD", msg.encode())
    else:
        msg = mc.command(
            vid,
            args.manager,
            args.cmd,
            seq,
            plan_name=getattr(args, "plan", Path()).name,
            plan_text=plan_text if args.cmd == "load" else "",
            reason=getattr(args, "reason", "") or f"auvctl ({mc.who()})",
        )
        if ring:
            auth.sign(msg, ring, auth.default_sender("auvctl"))
        lc.publish(f"{prefix}{vid}.MISSION_CMD", msg.encode())
    if radio is not None:
        return radio.wait(lc, args.timeout)
    acks = _wait_acks(lc, model, vid, seq, args.manager, args.timeout)
    if not acks:
        print(
            f"auvctl: no acknowledgement from {vid} {args.manager or '(any manager)'} within "
            f"{args.timeout:g} s (seq {seq})",
            file=sys.stderr,
        )
        return 3
    for a in acks:
        print(f"{vid} {a['manager']} {a['result']}: {a['message']}")
    return 0 if all(a["result"] == "ok" for a in acks) else 1


class RadioProgress:
    """Prints each state of the command as the shore gateway reports it. The
    managers' answer is in the acknowledged state's message (an acoustic
    command reaches them under another seq, its 24-bit counter)."""

    def __init__(self, lc: lcm.LCM, vid: str, seq: int) -> None:
        self.seq, self.last, self.failed, self.answer = seq, "", False, None
        lc.subscribe(rf"SHORE\.{vid}\.RADIO_CMD_STATUS", self._on)

    def _on(self, channel: str, data: bytes) -> None:
        m = decode(data)
        if m is None or getattr(m, "seq", None) != self.seq:
            return
        state = STATES[m.state] if 0 <= m.state < len(STATES) else str(m.state)
        pct = (
            f" {100 * m.bytes_held // max(m.bytes_total, 1)}%"
            if state in ("queued", "in flight") and m.route == "radio"
            else ""
        )
        line = f"{m.vehicle} {m.what} ({m.route}): {state}{pct}" + (f": {m.message}" if m.message else "")
        if line != self.last:
            print(line, flush=True)
            self.last = line
        self.failed = self.failed or state in ("expired", "refused")
        if state == "acknowledged":
            self.answer = m.message

    def wait(self, lc: lcm.LCM, timeout: float) -> int:
        """0 the managers answered ok, 1 not ok, expired or refused, 3 nothing in time."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and not self.failed and self.answer is None:
            lc.handle_timeout(50)
        if self.failed:
            return 1
        if self.answer is None:
            print(f"auvctl: not acknowledged within {timeout:g} s (seq {self.seq}): {self.last}", file=sys.stderr)
            return 3
        return 0 if " ok" in self.answer and not any(w in self.answer for w in (" rejected", " failed")) else 1


def _wait_acks(lc: lcm.LCM, model: Model, vid: str, seq: int, manager: str, timeout: float) -> list[dict]:
    deadline = time.monotonic() + timeout
    complete_at = None
    while time.monotonic() < deadline:
        lc.handle_timeout(50)
        v = model.vehicles.get(vid)
        if v is None:
            continue
        acks = [a for a in v["acks"] if a["seq"] == seq]
        expected = {manager} if manager else set(v["managers"])
        if acks and expected <= {a["manager"] for a in acks}:
            if manager:
                return acks
            complete_at = complete_at or time.monotonic()
            if time.monotonic() - complete_at >= SETTLE_S:
                return acks
    v = model.vehicles.get(vid)
    return [a for a in v["acks"] if a["seq"] == seq] if v else []


def _status(lc: lcm.LCM, model: Model, vid: str, args: argparse.Namespace) -> int:
    deadline = time.monotonic() + args.timeout
    first = None
    while time.monotonic() < deadline:
        lc.handle_timeout(50)
        v = model.vehicles.get(vid)
        if v and v["managers"] and (not args.manager or args.manager in v["managers"]):
            first = first or time.monotonic()
            if time.monotonic() - first >= 1.0:  # a second to hear every manager
                break
    v = model.vehicles.get(vid)
    if not v or not v["managers"] or (args.manager and args.manager not in v["managers"]):
        print(f"auvctl: nothing heard from {vid} {args.manager} within {args.timeout:g} s", file=sys.stderr)
        return 3
    if args.manager:
        v = dict(v, managers={args.manager: v["managers"][args.manager]})
    v = {k: x for k, x in v.items() if k != "acks"}
    if args.json:
        print(json.dumps(dict(v, t=model.t), indent=1))
        return 0
    print(f"{vid} at t={model.t:.1f} s")
    for name, m in sorted(v["managers"].items()):
        print(f"  {name}: {m['run']} {m['path']} ({m['time_in_state']:.1f} s in state, plan {m['plan']})")
        last = m["last"]
        if last["to"]:
            tests = " ".join(f"{k}={'true' if x else 'false'}" for k, x in last["tests"].items())
            print(
                f"    last: {last['from'] or '-'} -> {last['to']} at {last['t']:.1f} s"
                + (f" when {last['condition']}" if last["condition"] else "")
                + (f" [{tests}]" if tests else "")
            )
        if m.get("auth_refused"):
            reasons = ", ".join(f"{k} {n}" for k, n in m["auth_refused"].items())
            print(f"    commands refused by authentication: {reasons}")
    pos = v["nav"]
    if pos:
        print(
            f"  nav: N {pos['n']:.1f} E {pos['e']:.1f} depth {pos['depth']:.1f} m, "
            f"sigma {pos['sigma']:.1f} m, {' '.join(pos['flags']) or 'no aids'}"
        )
    if v["modem"]:
        print("  modem: " + ", ".join(f"{k} {x}" for k, x in v["modem"].items() if k != "last_refusal"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
