"""The team section of the mission report (a cooperative MCM run, docs/tools.md).

From the log: the team plugin's events (<V>.TEAM_EVENT, team_event_t), the
modems' frames and counters (<V>.MODEM_RX, <V>.MODEM_TX, <V>.MODEM_STATUS) and
the true field (SIM.TARGETS). Figures:

- per true target: first detection = the first CONTACT_NEW whose position is
  within the association radius of it (nearest object); identification = the
  first TARGET_IDENTIFIED naming one of its contacts (origin, number), or, for
  a target the RI vehicle merged under another name, within the radius of it;
  the time between them;
- mine-like targets identified by mission end (and called mine);
- false identifications: result mine on clutter or on nothing (a false alarm),
  not mine on a mine-like target;
- the RI route: every ROUTE event (its order of targets) and the RI track;
- link statistics per vehicle from its last MODEM_STATUS (sent, heard =
  received, lost, out of range, collided and deaf where the modem reports
  them, refused), and bytes per contact: the contact reports' share of the
  frames, from the codec's contact size times CONTACT_SENT events, over the
  contacts reported (the method used is named in the figures);
- takeovers: PEER_LOST and LINES_TAKEN events.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import numpy as np

from auvlcm.paths import ROOT
from tools.report.run_data import RunData

SCHEMA = ROOT / "c" / "plugins" / "team" / "team_link.schema"
# TEAM_SPEC section 2's contact message, used while the schema file is not in this tree
SPEC_CONTACT = [
    ("int", 0, 15, 1),
    ("int", 0, 1023, 1),
    ("fixed", -2000, 2000, 0.25),
    ("fixed", -2000, 2000, 0.25),
    ("fixed", 0, 12.7, 0.1),
    ("fixed", 0, 1, 0.01),
    ("int", 0, 15, 1),
    ("int", 0, 16383, 1),
]
ID_BITS = 4

# team_event_t kinds
CONTACT_NEW, CONTACT_SENT, CONTACT_ACKED, TARGET_QUEUED, TARGET_IDENTIFIED = 1, 2, 3, 4, 5
TARGET_NOT_FOUND, ROUTE, PEER_LOST, LINES_TAKEN, KEEP_CLEAR, IDENT_HEARD = 6, 7, 8, 9, 10, 11
RESULT_MINE, RESULT_NOT_MINE = 1, 2
KIND_TEAM = 2


def events(run: RunData) -> list[Any]:
    """Every team event of the run, in time order."""
    out = [m for ch in run.log.messages if ch.endswith(".TEAM_EVENT") for m in run.log.messages[ch]]
    return sorted(out, key=lambda m: m.utime)


def contact_bits(schema: Path = SCHEMA) -> tuple[int, str]:
    """Bits of one contact message (id included), and where the layout came from."""
    fields, source = SPEC_CONTACT, "TEAM_SPEC contact layout"
    if schema.is_file():
        fields, inside = [], False
        for line in schema.read_text().splitlines():
            words = line.split("#", 1)[0].split()
            if words[:1] == ["message"]:
                inside = len(words) > 1 and words[1] == "contact"
            elif inside and len(words) >= 4 and words[1] in ("int", "fixed"):
                step = float(words[4]) if words[1] == "fixed" and len(words) > 4 else 1.0
                fields.append((words[1], float(words[2]), float(words[3]), step))
        source = str(schema.relative_to(ROOT))
    bits = ID_BITS + sum(math.ceil(math.log2(round((hi - lo) / step) + 1)) for _k, lo, hi, step in fields)
    return bits, source


def _nearest(targets, north: float, east: float, radius: float) -> int:
    if not targets:
        return -1
    d = [math.hypot(t.north_m - north, t.east_m - east) for t in targets]
    k = int(np.argmin(d))
    return k if d[k] <= radius else -1


def target_table(run: RunData, evs: list, radius: float, t0: float) -> tuple[list[dict], list[dict]]:
    """Per true target its detection and identification; and the false identifications."""
    targets = run.targets()
    by_contact: dict[tuple[str, int], int] = {}
    rows = [
        {
            "id": int(t.id),
            "kind": "mine_like" if t.kind == 0 else "clutter",
            "north_m": float(t.north_m),
            "east_m": float(t.east_m),
            "detected_s": None,
            "detected_by": None,
            "identified_s": None,
            "result": None,
            "latency_s": None,
        }
        for t in targets
    ]
    for e in evs:
        if e.kind == CONTACT_NEW:
            k = _nearest(targets, e.north_m, e.east_m, radius)
            by_contact[(e.origin or e.vehicle, int(e.number))] = k
            if k >= 0 and rows[k]["detected_s"] is None:
                rows[k]["detected_s"], rows[k]["detected_by"] = e.utime / 1e6 - t0, e.vehicle
    false_ids = []
    for e in evs:
        if e.kind != TARGET_IDENTIFIED:
            continue
        k = by_contact.get((e.origin, int(e.number)), -1)
        if k < 0:
            k = _nearest(targets, e.north_m, e.east_m, radius)
        result = {RESULT_MINE: "mine", RESULT_NOT_MINE: "not_mine"}.get(int(e.result), str(e.result))
        t = e.utime / 1e6 - t0
        truth = rows[k]["kind"] if k >= 0 else "nothing"
        if (result == "mine" and truth != "mine_like") or (result == "not_mine" and truth == "mine_like"):
            false_ids.append(
                {
                    "time_s": t,
                    "vehicle": e.vehicle,
                    "target": f"{e.origin}:{e.number}",
                    "result": result,
                    "truth": truth,
                    "true_id": rows[k]["id"] if k >= 0 else None,
                }
            )
        if k >= 0 and rows[k]["identified_s"] is None:
            rows[k]["identified_s"], rows[k]["result"] = t, result
            if rows[k]["detected_s"] is not None:
                rows[k]["latency_s"] = t - rows[k]["detected_s"]
    return rows, false_ids


def link_stats(run: RunData, evs: list) -> dict:
    bits, source = contact_bits()
    out = {}
    for ch in sorted(c for c in run.log.messages if c.endswith(".MODEM_STATUS")):
        msgs = run.log.messages[ch]
        if not msgs:
            continue
        s = msgs[-1]
        vid = ch.split(".")[0]
        tx = [m for m in run.log.messages.get(f"{vid}.MODEM_TX", []) if m.kind == KIND_TEAM]
        sent_events = sum(1 for e in evs if e.vehicle == vid and e.kind == CONTACT_SENT)
        contacts = len({(e.origin or vid, e.number) for e in evs if e.vehicle == vid and e.kind == CONTACT_SENT})
        out[vid] = {
            "sent": int(s.sent),
            "heard": int(s.received),
            "lost": int(s.lost),
            "out_of_range": int(s.out_of_range),
            "collided": int(getattr(s, "collided", -1)) if hasattr(s, "collided") else None,
            "deaf": int(getattr(s, "deaf", -1)) if hasattr(s, "deaf") else None,
            "refused": int(s.refused_size + s.refused_rate + s.refused_invalid),
            "team_frames_queued": len(tx),
            "team_bytes_queued": int(sum(m.n_bytes for m in tx)),
            "contact_reports_sent": sent_events,
            "contacts_reported": contacts,
            "bytes_per_contact": (sent_events * bits / 8 / contacts) if contacts else None,
        }
    return {
        "per_vehicle": out,
        "contact_message_bits": bits,
        "bytes_per_contact_method": f"CONTACT_SENT events x {bits} bits ({source}) / contacts reported",
    }


def who_heard_whom(run: RunData, t0: float) -> dict[str, list[float]]:
    """'SRC->RECEIVER' -> arrival times [s] of the frames it heard."""
    out: dict[str, list[float]] = {}
    for ch in (c for c in run.log.messages if c.endswith(".MODEM_RX")):
        for m in run.log.messages[ch]:
            out.setdefault(f"{m.src_vehicle}->{m.vehicle}", []).append(m.utime / 1e6 - t0)
    return dict(sorted(out.items()))


def looks_stats(run: RunData, radius: float) -> dict:
    """Per vehicle with a LOOKS channel: looks, how many fell within `radius` of a true
    object, and how many of those gave its true kind (the sensor's p_correct, measured)."""
    targets = run.targets()
    out = {}
    for ch in sorted(c for c in run.log.messages if c.endswith(".LOOKS")):
        on, right = 0, 0
        for m in run.log.messages[ch]:
            k = _nearest(targets, m.north_m, m.east_m, radius)
            if k >= 0:
                on += 1
                right += (m.result == RESULT_MINE) == (targets[k].kind == 0)
        out[ch.split(".")[0]] = {"looks": len(run.log.messages[ch]), "on_objects": on, "right": right}
    return out


def ri_vehicles(run: RunData, evs: list) -> list[str]:
    team = (run.survey or {}).get("team") or {}
    if team.get("ri"):
        return list(team["ri"])
    return sorted({e.vehicle for e in evs if e.kind in (ROUTE, TARGET_QUEUED, TARGET_IDENTIFIED)})


def route_order(text: str) -> list[str]:
    return [f"{o}:{n}" for o, n in re.findall(r"([A-Za-z0-9_]+):(\d+)", text)]


def team_section(run: RunData, radius: float) -> dict | None:
    evs = events(run)
    if not evs and not any(c.endswith(".MODEM_STATUS") for c in run.log.messages):
        return None
    t0 = float(run.log["SIM.CLOCK"].t[0]) if "SIM.CLOCK" in run.log and len(run.log["SIM.CLOCK"].t) else 0.0
    rows, false_ids = target_table(run, evs, radius, t0)
    mines = [r for r in rows if r["kind"] == "mine_like"]
    lat = [r["latency_s"] for r in mines if r["latency_s"] is not None]  # the MCM figure: mines
    ri = ri_vehicles(run, evs)
    routes = [
        {"time_s": e.utime / 1e6 - t0, "vehicle": e.vehicle, "order": route_order(e.text)}
        for e in evs
        if e.kind == ROUTE
    ]
    takeovers = [
        {
            "time_s": e.utime / 1e6 - t0,
            "vehicle": e.vehicle,
            "event": "PEER_LOST" if e.kind == PEER_LOST else "LINES_TAKEN",
            "peer": e.origin,
            "text": e.text,
        }
        for e in evs
        if e.kind in (PEER_LOST, LINES_TAKEN)
    ]
    return {
        "targets": rows,
        "association_radius_m": radius,
        "mine_like_targets": len(mines),
        "mine_like_detected": sum(r["detected_s"] is not None for r in mines),
        "mine_like_identified": sum(r["identified_s"] is not None for r in mines),
        "mine_like_identified_as_mine": sum(r["result"] == "mine" for r in mines),
        "identifications": sum(e.kind == TARGET_IDENTIFIED for e in evs),
        "not_found": sum(e.kind == TARGET_NOT_FOUND for e in evs),
        "false_identifications": false_ids,
        "detect_to_identify_s": (
            {"mean": float(np.mean(lat)), "median": float(np.median(lat)), "max": float(np.max(lat)), "n": len(lat)}
            if lat
            else None
        ),
        "ri_vehicles": ri,
        "routes": routes,
        "takeovers": takeovers,
        "link": link_stats(run, evs),
        "looks": looks_stats(run, radius),
        "heard": {k: len(v) for k, v in who_heard_whom(run, t0).items()},
    }


def _f(x, digits=0) -> str:
    return "-" if x is None else f"{x:.{digits}f}"


def team_text(t: dict) -> list[str]:
    lines = [
        "team (TEAM_EVENT, MODEM_*; a target's detection = its first CONTACT_NEW within "
        f"{t['association_radius_m']:g} m)",
        f"  mine-like targets {t['mine_like_targets']}: detected {t['mine_like_detected']}, identified by the end "
        f"{t['mine_like_identified']} ({t['mine_like_identified_as_mine']} as mine); identifications "
        f"{t['identifications']}, not found {t['not_found']}, false {len(t['false_identifications'])}",
    ]
    d = t["detect_to_identify_s"]
    if d:
        lines.append(
            f"  mine-like, detection to identification: mean {d['mean'] / 60:.1f} min, median {d['median'] / 60:.1f} min, "
            f"max {d['max'] / 60:.1f} min over {d['n']} targets"
        )
    lines.append("  target  kind       detected [s] by      identified [s] result    latency [s]")
    for r in t["targets"]:
        if r["detected_s"] is None and r["identified_s"] is None and r["kind"] != "mine_like":
            continue
        lines.append(
            f"  {r['id']:>6}  {r['kind']:<10} {_f(r['detected_s']):>12} {r['detected_by'] or '-':<6} "
            f"{_f(r['identified_s']):>14} {r['result'] or '-':<9} {_f(r['latency_s']):>11}"
        )
    for f in t["false_identifications"]:
        lines.append(
            f"  FALSE identification at {f['time_s']:.0f} s by {f['vehicle']}: {f['target']} called "
            f"{f['result']}, truth {f['truth']}"
        )
    if t["routes"]:
        last = t["routes"][-1]
        lines.append(
            f"  RI route ({', '.join(t['ri_vehicles']) or '-'}): {len(t['routes'])} replans; last at "
            f"{last['time_s']:.0f} s: {' '.join(last['order']) or '(empty)'}"
        )
    for vid, lk in t.get("looks", {}).items():
        lines.append(f"  {vid} looks (LOOKS): {lk['looks']}, on an object {lk['on_objects']}, right kind {lk['right']}")
    link = t["link"]
    lines.append(f"  link per vehicle (bytes per contact: {link['bytes_per_contact_method']})")
    for vid, s in link["per_vehicle"].items():
        lines.append(
            f"    {vid}: sent {s['sent']}, heard {s['heard']}, lost {s['lost']}, out of range "
            f"{s['out_of_range']}, collided {_f(s['collided'])}, deaf {_f(s['deaf'])}, refused "
            f"{s['refused']}; contacts reported {s['contacts_reported']}, bytes per contact "
            f"{_f(s['bytes_per_contact'], 1)}"
        )
    if t["heard"]:
        lines.append("  heard (frames): " + ", ".join(f"{k} {v}" for k, v in t["heard"].items()))
    for x in t["takeovers"]:
        lines.append(
            f"  {x['event']} at {x['time_s']:.0f} s by {x['vehicle']}: peer {x['peer']}"
            + (f", lines {x['text']}" if x["text"] else "")
        )
    if not t["takeovers"]:
        lines.append("  takeovers: none")
    return lines
