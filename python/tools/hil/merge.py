"""One log of a run flown in several LCM worlds: their events in receive-time order.

Every world's recorder runs on the same machine's clock (network namespaces
share it), so the receive times order the events as they happened; events of
one world keep their order (a stable sort). A missing log (a vehicle computer
that never started) is skipped and said.
"""

from __future__ import annotations

from pathlib import Path

import lcm

from auvlcm.eventlog import Damage, read_raw


def merge_logs(
    logs: list[Path], out: Path, head: list[tuple[str, bytes]] = (), tail: list[tuple[str, bytes]] = ()
) -> dict[str, int]:
    """Write out from logs, head's messages before their first event and tail's
    after their last; the event count taken from each log."""
    events, counts = [], {}
    for k, path in enumerate(logs):
        if not path.exists():
            counts[str(path)] = -1
            continue
        n = 0
        for ev in read_raw(path, Damage()):
            events.append((ev.timestamp, k, n, ev.channel, ev.data))
            n += 1
        counts[str(path)] = n
    events.sort(key=lambda e: (e[0], e[1], e[2]))
    first = events[0][0] if events else 0
    last = events[-1][0] if events else 0
    log = lcm.EventLog(str(out), "w", overwrite=True)
    for channel, data in head:
        log.write_event(first, channel, data)
    for t, _, _, channel, data in events:
        log.write_event(t, channel, data)
    for channel, data in tail:
        log.write_event(last, channel, data)
    log.close()
    return counts
