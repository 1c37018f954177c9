"""The console's snapshot of the world: what every vehicle is doing now.

One writer (the LCM thread, or the log player) calls apply(); the web server's
client threads read under the same lock. Everything a page needs is either a
small "now" dictionary (rebuilt and serialised once per version, whatever the
number of pages) or an append-only Series (trails, contacts) that each page
receives incrementally from its own cursor.
"""

from __future__ import annotations

import json
import math
import threading
from collections import deque
from typing import Any

from sim import clock_modes
from tools.console import chasm_view, radio_view

RUN_NAMES = ("loading", "running", "paused", "done", "aborted", "failed")
NAV_BITS = (
    (1, "aligned"),
    (2, "dvl-bottom"),
    (4, "dvl-water"),
    (8, "gps"),
    (16, "lbl"),
    (32, "DEGRADED"),
    (64, "INVALID"),
)
LINK_KEEP_S = 8.0  # a heard modem frame stays on the map this long [sim s]
ACK_KEEP = 20  # acknowledgements kept per vehicle
WALL_STAMPED = ("agent_table_t",)  # stamped with the host's wall clock: not the world's time


def run_name(code: int) -> str:
    return RUN_NAMES[code] if 0 <= code < len(RUN_NAMES) else str(code)


class Series:
    """An append-only list that forgets its oldest items past a bound; readers
    keep a cursor (a count of items ever appended) and get what is new."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self.items: list[Any] = []
        self.base = 0  # items dropped from the front

    def append(self, item: Any) -> None:
        self.items.append(item)
        if len(self.items) > self.limit:  # drop a tenth at once: amortised O(1)
            cut = self.limit // 10 or 1
            del self.items[:cut]
            self.base += cut

    @property
    def end(self) -> int:
        return self.base + len(self.items)

    def since(self, cursor: int) -> tuple[bool, list[Any]]:
        """(reset, items): reset when the reader fell behind what is kept."""
        if cursor < self.base or cursor > self.end:
            return True, list(self.items)
        return False, self.items[cursor - self.base :]


class Trail(Series):
    """Positions [north, east] kept only when the vehicle moved min_step_m."""

    def __init__(self, limit: int = 6000, min_step_m: float = 0.5) -> None:
        super().__init__(limit)
        self.min_step2 = min_step_m * min_step_m

    def add(self, north: float, east: float) -> None:
        if self.items:
            n0, e0 = self.items[-1]
            if (north - n0) ** 2 + (east - e0) ** 2 < self.min_step2:
                return
        self.append([round(north, 2), round(east, 2)])


def _vehicle_id(channel: str) -> str:
    return channel.split(".", 1)[0]


class Model:
    def __init__(self) -> None:
        self.lock = threading.Condition()
        self.epoch = 0  # bumped by clear(): pages start over
        self.version = 0  # bumped by every change
        self.world_version = 0
        self.world: dict[str, Any] = {}  # survey, operating area, seabed: see live/world.py
        self.clear()

    # ------------------------------------------------------------- writing
    def clear(self) -> None:
        with self.lock:
            self.epoch += 1
            self.version += 1
            self.t = 0.0
            self.vehicles: dict[str, dict[str, Any]] = {}
            self.trails: dict[str, Trail] = {}
            self.contacts = Series(20000)
            self.targets: list[dict[str, Any]] = []
            self.links: deque = deque(maxlen=200)
            self.clock: dict[str, Any] = {}
            self.agents: dict[str, dict[str, Any]] = {}  # host -> its agent's process table
            self.counts = {"messages": 0, "ignored": 0}
            # the state view (chasm_view.py): "VEHICLE/MANAGER" -> the structure drawn, and what was refused
            self.structures: dict[str, dict[str, Any]] = {}
            self.structures_version = 0
            self.plans: dict[str, dict[str, Any]] = {}
            self._cache: tuple[int, str] | None = None

    def set_world(self, world: dict[str, Any]) -> None:
        with self.lock:
            self.world = world
            self.world_version += 1
            self.version += 1
            self.lock.notify_all()

    def _vehicle(self, vid: str) -> dict[str, Any]:
        v = self.vehicles.get(vid)
        if v is None:
            v = self.vehicles[vid] = {
                "id": vid,
                "truth": None,
                "nav": None,
                "nav_status": None,
                "managers": {},
                "modem": None,
                "frontseat": None,
                "radio": None,
                "acks": [],
            }
            self.trails[vid + ".true"] = Trail()
            self.trails[vid + ".nav"] = Trail()
        return v

    def apply(self, channel: str, msg: Any) -> bool:
        """Take one decoded message in; False if the console has no use for it."""
        handler = _HANDLERS.get(type(msg).__name__)
        with self.lock:
            self.counts["messages"] += 1
            if handler is None or not handler(self, channel, msg):
                self.counts["ignored"] += 1
                return False
            utime = getattr(msg, "utime", 0) if type(msg).__name__ not in WALL_STAMPED else 0
            if utime and utime / 1e6 > self.t:
                self.t = utime / 1e6
            self.version += 1
            self.lock.notify_all()
            return True

    def refuse_structure(self, channel: str, reason: str) -> None:
        """A message on a structure channel that does not decode: counted, with the reason, on its manager."""
        if ".PLAN." not in channel:
            return
        with self.lock:
            info = _plan_info(self, f"{_vehicle_id(channel)}/{channel.rsplit('.', 1)[-1]}")
            info["refused"] += 1
            info["reason"] = reason
            self.version += 1
            self.lock.notify_all()

    # ------------------------------------------------------------- reading
    def now_json(self) -> str:
        """Everything but the series, serialised once per version (call under lock)."""
        if self._cache is None or self._cache[0] != self.version:
            links = [ln for ln in self.links if self.t - ln["t"] <= LINK_KEEP_S]
            now = {
                "t": self.t,
                "epoch": self.epoch,
                "world_version": self.world_version,
                "vehicles": self.vehicles,
                "targets": self.targets,
                "links": links,
                "clock": self.clock,
                "agents": self.agents,
                "counts": self.counts,
                "plans": self.plans,
            }
            self._cache = (self.version, json.dumps(now, separators=(",", ":")))
        return self._cache[1]

    def structures_since(self, sent: dict[str, str]) -> dict[str, Any]:
        """The structures a page has not got yet (sent: key -> plan_id, updated in place)."""
        out = {k: st for k, st in self.structures.items() if sent.get(k) != st["id"]}
        for k, st in out.items():
            sent[k] = st["id"]
        return out

    def series_since(self, cursors: dict[str, int], fresh: bool = False) -> dict[str, Any]:
        """New trail points and contacts for one page; cursors are updated in place.
        fresh: the page starts over (first push, or the model was cleared), so
        every series is sent whole with reset set, empty ones included."""
        out: dict[str, Any] = {}
        for name, series in list(self.trails.items()) + [("contacts", self.contacts)]:
            reset, items = series.since(-1 if fresh else cursors.get(name, 0))
            if reset or items:
                out[name] = {"reset": reset, "add": items}
            cursors[name] = series.end
        return out


# ----------------------------------------------------------------- handlers
def _truth(m: Model, ch: str, msg: Any) -> bool:
    if not ch.endswith(".TRUTH"):
        return False
    vid = _vehicle_id(ch)
    v = m._vehicle(vid)
    n, e, d = msg.eta[0], msg.eta[1], msg.eta[2]
    v["truth"] = {
        "n": round(n, 2),
        "e": round(e, 2),
        "depth": round(d, 2),
        "heading": round(msg.eta[5] % (2 * math.pi), 4),
        "altitude": round(msg.altitude_m, 2),
        "t": msg.utime / 1e6,
    }
    m.trails[vid + ".true"].add(n, e)
    return True


def _nav(m: Model, ch: str, msg: Any) -> bool:
    if not ch.endswith(".NAV"):
        return False
    vid = _vehicle_id(ch)
    v = m._vehicle(vid)
    flags = [name for bit, name in NAV_BITS if msg.status & bit]
    v["nav"] = {
        "n": round(msg.north_m, 2),
        "e": round(msg.east_m, 2),
        "depth": round(msg.depth_m, 2),
        "heading": round(msg.heading_rad, 4),
        "altitude": round(msg.altitude_m, 2),
        "speed": round(msg.speed_over_ground_mps, 2),
        "flags": flags,
        "sigma": round(math.sqrt(max(0.0, msg.position_cov_m2[0][0] + msg.position_cov_m2[1][1])), 2),
        "t": msg.utime / 1e6,
    }
    m.trails[vid + ".nav"].add(msg.north_m, msg.east_m)
    return True


def _nav_status(m: Model, ch: str, msg: Any) -> bool:
    v = m._vehicle(_vehicle_id(ch))
    v["nav_status"] = {
        "trusted": bool(msg.trusted),
        "sigma": round(msg.position_sigma_m, 2),
        "heading_sigma_deg": round(math.degrees(msg.heading_sigma_rad), 2),
        "accepted": list(msg.accepted),
        "rejected": list(msg.rejected),
    }
    return True


def _plan_info(m: Model, key: str) -> dict[str, Any]:
    info = m.plans.get(key)
    if info is None:
        info = m.plans[key] = {"id": "", "refused": 0, "reason": "", "mismatched": 0}
    return info


def _structure(m: Model, ch: str, msg: Any) -> bool:
    """A manager's plan structure (<VEHICLE>.PLAN.<MANAGER>): drawn only if it holds together."""
    if ".PLAN." not in ch:
        return False
    vid = _vehicle_id(ch)
    m._vehicle(vid)
    key = f"{vid}/{msg.manager or ch.rsplit('.', 1)[-1]}"
    info = _plan_info(m, key)
    if key in m.structures and m.structures[key]["id"] == msg.plan_id and not msg.truncated:
        return True  # sent again: the same plan
    try:
        m.structures[key] = chasm_view.check_structure(msg)
    except (chasm_view.BadStructure, IndexError) as exc:
        info["refused"] += 1
        info["reason"] = str(exc)
        return True
    info["id"] = msg.plan_id
    m.structures_version += 1
    return True


def _chasm(m: Model, ch: str, msg: Any) -> bool:
    if ".CHASM." not in ch:
        return False
    v = m._vehicle(_vehicle_id(ch))
    name = msg.manager or ch.rsplit(".", 1)[-1]
    old = v["managers"].get(name)
    key = f"{_vehicle_id(ch)}/{name}"
    drawn = m.structures.get(key)
    if drawn is not None and msg.plan_id != drawn["id"]:
        _plan_info(m, key)["mismatched"] += 1
    v["managers"][name] = {
        "view": chasm_view.status_view(msg, old.get("view") if old else None),
        "run": run_name(msg.run_state),
        "path": "/".join(msg.active_path),
        "time_in_state": round(msg.time_in_state_s[-1], 1) if msg.path_len else 0.0,
        "plan": msg.plan,
        "cycle": msg.cycle,
        "last": {
            "t": msg.last_transition_utime / 1e6,
            "from": msg.last_from,
            "to": msg.last_to,
            "condition": msg.last_condition,
            "tests": {n: bool(x) for n, x in zip(msg.test_name, msg.test_value)},
        },
        "decode_errors": msg.decode_errors,
        "commands_refused": msg.commands_refused,
        # refused by authentication, by reason (docs/security.md); only reasons that happened
        "auth_refused": {
            k: n
            for k, n in (
                ("unsigned", msg.auth_unsigned),
                ("unknown_key", msg.auth_unknown_key),
                ("bad_mac", msg.auth_bad_mac),
                ("replay", msg.auth_replay),
                ("stale", msg.auth_stale),
            )
            if n
        },
    }
    return True


def _contact(m: Model, ch: str, msg: Any) -> bool:
    m._vehicle(_vehicle_id(ch))
    m.contacts.append(
        {
            "v": msg.vehicle,
            "id": msg.contact_id,
            "n": round(msg.north_m, 2),
            "e": round(msg.east_m, 2),
            "class": msg.classification,
            "conf": round(float(msg.confidence), 2),
            "t": msg.utime / 1e6,
        }
    )
    return True


def _targets(m: Model, ch: str, msg: Any) -> bool:
    m.targets = [
        {"id": t.id, "n": t.north_m, "e": t.east_m, "kind": "mine_like" if t.kind == 0 else "clutter"}
        for t in msg.targets
    ]
    return True


def _modem_rx(m: Model, ch: str, msg: Any) -> bool:
    m.links.append(
        {
            "src": msg.src_vehicle,
            "dst": msg.vehicle,
            "seq": msg.seq,
            "t": msg.utime / 1e6,
            "range": round(msg.range_m, 1),
        }
    )
    return True


def _modem_status(m: Model, ch: str, msg: Any) -> bool:
    v = m._vehicle(_vehicle_id(ch))
    v["modem"] = {
        k: getattr(msg, k)
        for k in (
            "sent",
            "received",
            "lost",
            "out_of_range",
            "collided",
            "deaf",
            "refused_size",
            "refused_rate",
            "refused_invalid",
        )
    }
    v["modem"]["last_refusal"] = msg.last_refusal
    return True


FRONTSEAT_STATES = ("not connected", "silent", "frontseat", "payload", "error", "manual")


def _frontseat(m: Model, ch: str, msg: Any) -> bool:
    """A commercial vehicle's frontseat as auv-frontseat sees it (docs/frontseat.md):
    who flies the vehicle now (the payload's requests, the frontseat's own
    mission, or an operator), its error, and how long since it was heard."""
    if not ch.endswith(".FRONTSEAT"):
        return False
    v = m._vehicle(_vehicle_id(ch))
    state = FRONTSEAT_STATES[msg.state] if 0 <= msg.state < len(FRONTSEAT_STATES) else str(msg.state)
    v["frontseat"] = {
        "protocol": msg.protocol,
        "state": state,
        # who has control, in the operator's words
        "control": "payload" if msg.has_control else ("operator" if state == "manual" else "frontseat"),
        "has_control": bool(msg.has_control),
        "requesting": bool(msg.requesting),
        "mode": msg.mode,
        "error": msg.error_text if msg.error else "",
        "age_s": round(msg.last_message_age_s, 1),
        "granted": msg.control_granted,
        "lost": msg.control_lost,
        "refused": msg.setpoints_refused,
        "clamped": msg.setpoints_clamped,
        "last_refusal": msg.last_refusal,
        "t": msg.utime / 1e6,
    }
    return True


def _ack(m: Model, ch: str, msg: Any) -> bool:
    v = m._vehicle(msg.vehicle if ch.startswith("SHORE.") else _vehicle_id(ch))  # relayed home by the radio
    v["acks"] = (
        v["acks"]
        + [
            {
                "seq": msg.seq,
                "manager": msg.manager,
                "message": msg.message,
                "result": ("ok", "rejected", "failed")[msg.result] if 0 <= msg.result <= 2 else str(msg.result),
            }
        ]
    )[-ACK_KEEP:]
    return True


def _clock(m: Model, ch: str, msg: Any) -> bool:
    m.clock = {"server": msg.server_id, "mode": clock_modes.name_of_wire(msg.mode), "warp": msg.warp}
    return True


PROC_STATES = ("running", "back-off", "exited", "failed", "stopped")


def _agent(m: Model, ch: str, msg: Any) -> bool:
    """A host agent's process table (AGENT.<HOST>.PROCS, python/tools/hosts/agent.py)."""
    m.agents[msg.host] = {
        "host": msg.host,
        "pid": msg.agent_pid,
        "run": msg.run,
        "status": msg.status,
        "launcher_silent_s": msg.launcher_silent_s,
        "procs": [
            {
                "name": p.name,
                "pid": p.pid,
                "state": PROC_STATES[p.state] if 0 <= p.state < len(PROC_STATES) else str(p.state),
                "exit_code": p.exit_code,
                "restarts": p.restarts,
                "cpu": p.cpu_load,
                "rss_mb": p.rss_bytes / 1e6,
                "uptime_s": p.uptime_s,
            }
            for p in msg.procs
        ],
    }
    return True


_HANDLERS = {
    "ground_truth_t": _truth,
    "nav_solution_t": _nav,
    "nav_filter_status_t": _nav_status,
    "chasm_status_t": _chasm,
    "chasm_structure_t": _structure,
    "sidescan_contact_t": _contact,
    "target_field_t": _targets,
    "modem_rx_t": _modem_rx,
    "modem_status_t": _modem_status,
    "frontseat_status_t": _frontseat,
    "mission_ack_t": _ack,
    "sim_clock_t": _clock,
    "agent_table_t": _agent,
    **radio_view.HANDLERS,
}

# Only these channels are decoded at all (liblcm filters by this regex in C).
CHANNELS = (
    r"[A-Za-z0-9_]+\.(TRUTH|NAV|NAV_STATUS|CONTACTS|MODEM_RX|MODEM_STATUS|MISSION_ACK|FRONTSEAT)"
    r"|[A-Za-z0-9_]+\.(CHASM|PLAN)\.[A-Za-z0-9_]+|SIM\.(CLOCK|TARGETS|ANNOTATION|ENV)"
    r"|AGENT\.[A-Za-z0-9_.-]+\.PROCS" + radio_view.CHANNELS
)
