"""`auv-launch SCENARIO --agents`: the whole scenario through the host agents
(docs/hosts.md). Each host's agent gets the scenario and starts its part;
this process keeps the global clock (time.source: launcher) and the mission
watch, exactly as auv-launch does, sends a keepalive every second (the
agents' dead-man time, --deadman), and at the end stops every part. A
process that fails on any host (its agent's table says so), an agent silent
for 5 s, or an agent that no longer runs the run (restarted) ends the run as
a death does in auv-launch (exit 5): the launcher outlives its agents.
"""

from __future__ import annotations

import threading
import time

import lcm

from auv import agent_command_t as C
from auv import agent_process_t, agent_table_t
from tools.hosts.agent import channels
from tools.hosts.agentctl import Control, parse_rule, report

AGENT_SILENT_S = 5.0  # no process table for this long: the agent (and its part) is gone


class Keepalive(threading.Thread):
    """Keepalives out, process tables in, on an LCM object of its own."""

    def __init__(self, url: str, ctl: Control, hosts: list[str], run: str) -> None:
        super().__init__(daemon=True)
        self.lc, self.ctl, self.hosts, self.run_name = lcm.LCM(url), ctl, hosts, run
        self.failed = ""
        self.done = False
        self.heard = {h: time.monotonic() for h in hosts}
        for h in hosts:
            self.lc.subscribe(channels(h)[2], self.on_table)

    def on_table(self, _c: str, data: bytes) -> None:
        t = agent_table_t.decode(data)
        self.heard[t.host] = time.monotonic()
        if t.run != self.run_name and not self.failed:  # a new agent: the part it ran is gone
            self.failed = f"the agent of host {t.host} no longer runs '{self.run_name}' ({t.status or 'idle'})"
        bad = [p for p in t.procs if p.state == agent_process_t.STATE_FAILED]
        if t.run == self.run_name and bad and not self.failed:
            self.failed = f"{bad[0].name} on host {t.host} failed (exit status {bad[0].exit_code})"

    def run(self) -> None:
        next_alive = 0.0
        while not self.done:
            if time.monotonic() >= next_alive:
                next_alive = time.monotonic() + 1.0
                silent = [h for h, t in self.heard.items() if time.monotonic() - t > AGENT_SILENT_S]
                if silent and not self.failed:
                    self.failed = f"the agent of host {silent[0]} is silent for {AGENT_SILENT_S:g} s (dead?)"
                for h in self.hosts:
                    keepalive = self.ctl.command(h, C.CMD_KEEPALIVE, run=self.run_name)
                    self.lc.publish(channels(h)[0], self.ctl.signed(keepalive))
            self.lc.handle_timeout(100)


def run_on_agents(sc, args, url: str, sim_configs: dict, navs: dict, ring=None) -> tuple[str, object]:
    """Start, watch and stop the run; returns (result, launcher) for auv-launch's summary.
    ring: the scenario's team keys (docs/security.md): every command is signed with it."""
    from tools.launch.launcher import Launcher

    rules = [parse_rule(r) for r in args.restart]
    run_name = sc.name
    ctl = Control(url, ring)
    starts = [
        ctl.command(
            h, C.CMD_START, run=run_name, path=str(sc.path), text=sc.text, deadman_s=args.deadman, restart=rules
        )
        for h in sc.hosts
    ]
    answers = ctl.send_all(starts, args.agent_timeout)
    args.host = None
    launcher = Launcher(sc, args, url, sim_configs, navs, agents=True)  # the log host's agent records
    if report(answers):
        launcher.stop_reason = "not every agent started its part (above)"
        ctl.send_all([ctl.command(h, C.CMD_STOP, run=run_name) for h in sc.hosts], args.agent_timeout)
        return "died", launcher
    keep = Keepalive(url, ctl, sc.hosts, run_name)
    keep.start()
    result = "died"
    try:
        if sc.log_enabled:
            time.sleep(0.5)  # the logger has just started on its host
            launcher.annotate()
        stop = lambda: args.stop_flag["stop"] or bool(keep.failed)  # noqa: E731
        result = launcher.wait_ready(stop) or launcher.supervise(stop)
        if keep.failed:
            result, launcher.stop_reason = "died", keep.failed
    except RuntimeError as exc:
        launcher.stop_reason = str(exc)
    finally:
        keep.done = True
        keep.join()
        launcher.stop_all(result)
        report(ctl.send_all([ctl.command(h, C.CMD_STOP, run=run_name) for h in sc.hosts], args.agent_timeout))
    return result, launcher
