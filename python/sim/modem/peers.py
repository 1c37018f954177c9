"""Peer reports through the modem: the vehicle's own report out, others' in.

Out: the comms plugin's peer_report behavior writes <VEHICLE>.PEER_REPORT
every manager cycle and increments its seq when a report is due; a new seq
becomes one KIND_NAV_REPORT broadcast frame whose payload is the encoded
peer_report_t. In: a received KIND_NAV_REPORT frame is decoded and published
on <VEHICLE>.PEER.<SENDER>, one channel per peer, so a plan binds each peer as
a whole fixed-layout message (docs/managers.md).
"""

from __future__ import annotations

from auv import modem_rx_t, modem_tx_t, peer_report_t
from auvlcm.decode import DecodeError, decode_strict


def report_frame(report: peer_report_t, vehicle: str) -> modem_tx_t:
    """The broadcast frame that carries this vehicle's report."""
    r = peer_report_t.decode(report.encode())  # a copy, with the payload's fields set
    r.vehicle, r.heard_by = vehicle, ""
    payload = r.encode()
    m = modem_tx_t()
    m.utime, m.vehicle, m.dst_vehicle, m.seq = report.utime, vehicle, "", report.seq
    m.kind, m.n_bytes, m.payload = modem_tx_t.KIND_NAV_REPORT, len(payload), payload
    return m


def heard_report(rx: modem_rx_t) -> peer_report_t:
    """The report in a received KIND_NAV_REPORT frame; DecodeError if it is not one."""
    r = decode_strict(peer_report_t, bytes(rx.payload))
    if r.vehicle != rx.src_vehicle:
        raise DecodeError(f"report describes {r.vehicle!r} but was sent by {rx.src_vehicle!r}", "malformed")
    r.heard_by = rx.vehicle
    return r
