"""auv-radio-sim: the surface radio of a simulated world (docs/radio.md).

    auv-radio-sim --vehicles AUV1,AUV2 [--clock sim|system] [--bitrate-bps 115200] ...

In:  <VEHICLE>.TRUTH (where each vehicle is: the radio is part of the world),
     RADIO.TX.<NODE> (radio_frame_t from the gateways), SIM.CLOCK (--clock sim).
     SHORE.MODEM_TX (modem_tx_t: the shore gateway's acoustic commands).
Out: RADIO.RX.<NODE> (the frames that arrived), <VEHICLE>.RADIO_LINK
     (radio_link_t: 1 Hz and at every change of the link), SIM.ACOUSTIC (the
     shore modem's frames, from the shore station's transducer at
     --shore-modem-depth-m: the vehicles' simulated modems hear them as any
     other frame), a summary at exit.

With --shore-lcm-url URL the shore is a world of its own (its network at sea): RADIO.TX/RX.SHORE
and SHORE.MODEM_TX are on that LCM, with a copy of each SIM.CLOCK; nothing else crosses.

With --pipe AUV1=PATH a vehicle's radio is a byte pipe instead (sim.radio.pipe_node):
a pseudo-terminal at PATH where its gateway (auv-radio, a driver) reads and writes
the framed frames as on a real radio modem; RADIO.RX/TX.AUV1 are then not used.

Every setting of the model (sim.radio.link.RadioConfig) is a flag:
--bitrate-bps, --latency-s, --loss, --max-range-m, --antenna-height-m,
--wave-height-m, --shore-north-m, --shore-east-m, ...
"""

from __future__ import annotations

import argparse
import dataclasses
import select
import signal
import sys
import time

import lcm

from auv import ground_truth_t, modem_status_t, modem_tx_t, radio_frame_t, radio_link_t, sim_clock_t
from auvlcm import programs
from auvlcm.rx import Receiver
from auvlcm.url import check_local, default_url, with_receive_buffer
from sim.modem.config import ModemConfig
from sim.modem.transmitter import Transmitter
from sim.multihil.lockstep import Participation
from sim.radio.link import SHORE, RadioConfig, RadioLink
from sim.radio.pipe_node import PipeNode, parse_pipes

NODE_RE = r"[A-Za-z0-9_]+"


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="auv-radio-sim", description=__doc__.split("\n\n")[0])
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)", default=None)
    ap.add_argument("--vehicles", required=True, help="comma-separated vehicle ids")
    ap.add_argument("--clock", choices=("sim", "system"), default="sim", help="SIM.CLOCK or this machine's")
    ap.add_argument("--pipe", default="", metavar="NODE=PATH,...", help="a node's radio as a pty at PATH")
    ap.add_argument("--shore-lcm-url", default="", help="the shore's own LCM (default: the same as the vehicles')")
    ap.add_argument("--lockstep-name", default="", help="take part in a lockstep world under this name")
    ap.add_argument("--shore-modem-depth-m", type=float, default=2.0, help="the shore modem's transducer depth")
    for f in dataclasses.fields(RadioConfig):
        ap.add_argument("--" + f.name.replace("_", "-"), type=type(f.default), default=f.default, metavar="X")
    return ap


class RadioSim:
    def __init__(
        self, lc: lcm.LCM, cfg: RadioConfig, vehicles: list[str], sim_clock: bool, shore_lc: lcm.LCM | None = None
    ) -> None:
        """shore_lc: the shore's own LCM (None: the vehicles'), where RADIO.TX/RX.SHORE,
        SHORE.MODEM_TX and a copy of SIM.CLOCK are."""
        self.lc, self.cfg, self.vehicles = lc, cfg, vehicles
        self.shore_lc = shore_lc or lc
        self.link = RadioLink(cfg, vehicles)
        self.sim_clock = sim_clock
        self.now: float | None = None if sim_clock else time.time()
        self.was_up: dict[str, bool] = {}
        self.next_status = 0.0
        self.seq = 0
        self.rx = Receiver(lc)
        for v in vehicles:
            self.rx.subscribe(f"{v}\\.TRUTH", ground_truth_t, self._on_truth)
        shore_rx = self.rx if shore_lc is None else Receiver(shore_lc)
        nodes = NODE_RE if shore_lc is None else "(" + "|".join(vehicles) + ")"
        self.rx.subscribe(f"RADIO\\.TX\\.{nodes}", radio_frame_t, self._on_frame)
        if shore_lc is not None:
            shore_rx.subscribe("RADIO\\.TX\\.SHORE", radio_frame_t, self._on_frame)
        if sim_clock:
            self.rx.subscribe("SIM\\.CLOCK", sim_clock_t, self._on_clock)
        self.refused = 0
        self.shore_modem = Transmitter(ModemConfig(), SHORE, modem_status_t())
        self.shore_modem_depth_m = 2.0
        self.modem_requests: list[modem_tx_t] = []
        shore_rx.subscribe("SHORE\\.MODEM_TX", modem_tx_t, lambda c, m: self.modem_requests.append(m))
        self.receivers = [self.rx] if shore_lc is None else [self.rx, shore_rx]
        self.pipes: dict[str, PipeNode] = {}
        self.part: Participation | None = None

    def pipes_open(self) -> bool:
        """Every pipe has its reader (a gateway opened the pty)."""
        return all(p.transport.connected() for p in self.pipes.values())

    def serve(self, timeout_s: float) -> None:
        """Waits for either LCM or a pipe's bytes (timeout_s at most), and takes them."""
        by_fd = {fd: p for p in self.pipes.values() for fd in p.fds()}
        lcms = {lc.fileno(): lc for lc in (self.lc, self.shore_lc)}
        ready, _, _ = select.select([*lcms, *by_fd], [], [], timeout_s)
        for fd in ready:
            if fd in lcms:
                lcms[fd].handle()
            else:
                p = by_fd[fd]
                for f in p.read(fd):
                    self._on_frame(f"RADIO.TX.{p.node}", f)
        for p in self.pipes.values():
            p.flush()

    def _on_truth(self, channel: str, m: ground_truth_t) -> None:
        v = channel.split(".", 1)[0]
        self.link.set_position(v, m.eta[0], m.eta[1], m.eta[2])

    def take_part(self, name: str) -> None:
        """A participant of a lockstep world: each lockstep step is reported done
        once the model has stepped to it, so the world never runs ahead of the radio."""
        self.part = Participation(name, lambda m: self.lc.publish("SIM.LOCKSTEP", m.encode()))

    def _on_clock(self, channel: str, m: sim_clock_t) -> None:
        t = m.utime * 1e-6
        lock = self.part is not None and m.mode == sim_clock_t.MODE_LOCKSTEP
        if self.shore_lc is not self.lc:
            self.shore_lc.publish("SIM.CLOCK", m.encode())  # the shore's tools follow the world's time
        if lock:
            self.part.on_clock(m.step, m.utime)
        if self.now is None or t > self.now:
            self.now = t
            self.step()
        if lock:
            self.part.done()

    def _on_frame(self, channel: str, f: radio_frame_t) -> None:
        src = channel.rsplit(".", 1)[1]
        if self.now is None or f.src != src or f.n_bytes != len(f.payload):
            self.refused += 1
            return
        self.link.send(src, f.dst, bytes(f.payload), self.now)

    def step(self) -> None:
        assert self.now is not None
        for fr in self.link.step(self.now):
            out = radio_frame_t()
            self.seq += 1
            out.utime, out.src, out.dst, out.seq = round(fr.t_arrive * 1e6), fr.src, fr.dst, self.seq
            out.n_bytes, out.payload = len(fr.payload), fr.payload
            pipe = self.pipes.get(fr.dst)
            if pipe is not None:
                pipe.write(out.encode())
            else:
                (self.shore_lc if fr.dst == SHORE else self.lc).publish(f"RADIO.RX.{fr.dst}", out.encode())
        self._shore_modem()
        due = self.now >= self.next_status - 1e-6  # a period of 0.05 s adds up to a hair over the clock
        for v in self.vehicles:
            up = self.link.up(v, SHORE)
            if due or self.was_up.get(v) != up:
                self.was_up[v] = up
                self._publish_link(v, up)
        if due:
            self.next_status = self.now + self.cfg.status_period_s

    def _shore_modem(self) -> None:
        """The shore's acoustic frames go into the water from the shore station."""
        assert self.now is not None
        pos = (self.cfg.shore_north_m, self.cfg.shore_east_m, self.shore_modem_depth_m)
        for m in [m for m in self.modem_requests if m.utime * 1e-6 <= self.now][:1]:
            out = self.shore_modem.send(self.now, pos, m)
            if isinstance(out, str):
                if out.startswith("busy"):
                    return  # the modem is still sending: try at the next step
                print(f"auv-radio-sim: shore modem refused a frame: {out}", file=sys.stderr)
            else:
                self.lc.publish("SIM.ACOUSTIC", out.encode())
            self.modem_requests.remove(m)

    def _publish_link(self, v: str, up: bool) -> None:
        m = radio_link_t()
        c = self.link.counts[v]
        m.utime, m.vehicle, m.up, m.antenna_clear = round(self.now * 1e6), v, up, self.link.clear(v)
        m.depth_m, m.range_m, m.bitrate_bps = (
            self.link.nodes[v].depth,
            self.link.range_m(v, SHORE),
            self.cfg.bitrate_bps,
        )
        m.frames_sent, m.frames_delivered = c.sent, c.delivered
        m.frames_lost, m.frames_dropped, m.bytes_delivered = c.lost, c.dropped, c.bytes_delivered
        m.queue_bytes = self.link.queued(v)
        self.lc.publish(f"{v}.RADIO_LINK", m.encode())

    def summary(self) -> str:
        parts = [
            f"{n}: sent {c.sent} delivered {c.delivered} lost {c.lost} dropped {c.dropped}"
            for n, c in self.link.counts.items()
        ]
        reasons = ", ".join(f"{k} {v}" for k, v in sorted(self.link.drop_reasons.items()))
        return (
            "auv-radio-sim: "
            + "; ".join(parts)
            + (f" (drops: {reasons})" if reasons else "")
            + (f"; refused {self.refused} frames" if self.refused else "")
            + "".join(f"; {p.summary()}" for p in self.pipes.values())
            + (f"; lockstep: {self.part.last_done + 1} steps reported" if self.part is not None else "")
            + f"; heard {sum(s.stats.delivered for r in self.receivers for s in r.subscriptions)} messages, clock at {self.now or 0:.2f} s"
        )


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    try:
        url = check_local(args.url or default_url())
        shore_url = check_local(args.shore_lcm_url) if args.shore_lcm_url else None
        pipes = parse_pipes(args.pipe)
    except ValueError as exc:
        print(f"auv-radio-sim: {exc}", file=sys.stderr)
        return 2
    cfg = RadioConfig(**{f.name: getattr(args, f.name) for f in dataclasses.fields(RadioConfig)})
    vehicles = [v for v in args.vehicles.split(",") if v]
    lc = lcm.LCM(with_receive_buffer(url))  # a 20 kB upload is many datagrams: none may be lost
    shore_lc = lcm.LCM(with_receive_buffer(shore_url)) if shore_url and shore_url != url else None
    sim = RadioSim(lc, cfg, vehicles, args.clock == "sim", shore_lc)
    sim.shore_modem_depth_m = args.shore_modem_depth_m
    sim.pipes = {node: PipeNode(node, path) for node, path in pipes.items()}
    if args.lockstep_name:
        sim.take_part(args.lockstep_name)
    stop = []
    signal.signal(signal.SIGINT, lambda *_: stop.append(1))
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    print("auv-radio-sim: ready", flush=True)  # subscribed: what is published from now on is heard
    while not stop:
        try:
            sim.serve(0.01)
        except OSError:  # EINTR from the signal that stops us: the loop checks
            continue
        if sim.part is not None and (sim.part.seen_clock or sim.pipes_open()):
            # registers once every vehicle's gateway has its radio open (the world
            # then starts with them listening), or repeats a report nobody acted on
            sim.part.poll()
        if not sim.sim_clock:
            sim.now = time.time()
            sim.step()
    print(sim.summary(), file=sys.stderr)
    for p in sim.pipes.values():
        p.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
