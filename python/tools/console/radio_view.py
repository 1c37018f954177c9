"""The console's view of the surface radio (docs/radio.md): per vehicle, the
link as the radio model reports it (<VEHICLE>.RADIO_LINK), the commands sent
through the shore gateway with their state and progress
(SHORE.<VEHICLE>.RADIO_CMD_STATUS) and the last status home
(SHORE.<VEHICLE>.RADIO_REPORT; the page shows its age).

The handlers take the model (tools.console.model.Model) and fill
vehicle["radio"]; they are registered in the model's handler table.
"""

from __future__ import annotations

from typing import Any

STATES = ("queued", "in flight", "delivered", "acknowledged", "expired", "refused")
RUN_STATES = ("loading", "running", "paused", "done", "aborted", "failed")
COMMANDS_KEPT = 8  # per vehicle, newest last

CHANNELS = r"|SHORE\.[A-Za-z0-9_]+\.(RADIO_CMD_STATUS|RADIO_REPORT|MISSION_ACK)|[A-Za-z0-9_]+\.RADIO_LINK"


def _radio(m: Any, vid: str) -> dict[str, Any]:
    v = m._vehicle(vid)
    if v.get("radio") is None:
        v["radio"] = {"link": None, "commands": [], "report": None}
    return v["radio"]


def link(m: Any, ch: str, msg: Any) -> bool:
    _radio(m, msg.vehicle)["link"] = {
        "up": bool(msg.up),
        "clear": bool(msg.antenna_clear),
        "range_m": round(msg.range_m, 1),
        "bitrate_bps": msg.bitrate_bps,
        "delivered": msg.frames_delivered,
        "lost": msg.frames_lost,
        "dropped": msg.frames_dropped,
        "t": msg.utime / 1e6,
    }
    return True


def command_status(m: Any, ch: str, msg: Any) -> bool:
    r = _radio(m, msg.vehicle)
    entry = {
        "id": str(msg.transfer_id),
        "seq": msg.seq,
        "what": msg.what,
        "state": STATES[msg.state] if 0 <= msg.state < len(STATES) else str(msg.state),
        "route": msg.route,
        "held": msg.bytes_held,
        "total": msg.bytes_total,
        "message": msg.message,
        "t": msg.utime / 1e6,
    }
    others = [c for c in r["commands"] if not (c["id"] == entry["id"] and c["seq"] == entry["seq"])]
    r["commands"] = (others + [entry])[-COMMANDS_KEPT:]
    return True


def report(m: Any, ch: str, msg: Any) -> bool:
    _radio(m, msg.vehicle)["report"] = {
        "t": msg.utime / 1e6,
        "n": round(msg.north_m, 1),
        "e": round(msg.east_m, 1),
        "depth": round(msg.depth_m, 1),
        "mission": msg.mission,
        "contacts": msg.contacts,
        "transfers": msg.n_transfers,
        "refused": msg.refused,
    }
    return True


HANDLERS = {"radio_link_t": link, "radio_command_status_t": command_status, "radio_report_t": report}
