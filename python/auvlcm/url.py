"""LCM URLs: the project's default, and the rule that traffic stays local.

udpm with ttl=0 never leaves the host. A TTL of 1 is allowed only where the caller
says it runs inside a network namespace that it created (multi-host tests).
"""

from __future__ import annotations

import os
import re
from urllib.parse import parse_qs, urlparse

DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"


def default_url() -> str:
    """$LCM_DEFAULT_URL if set (as liblcm itself reads), else the project default."""
    return os.environ.get("LCM_DEFAULT_URL") or DEFAULT_URL


# Set by a test that runs processes inside network namespaces it created
# (tests/multihil/netns.py): there, ttl=1 reaches only the test's own hosts.
NETNS_ENV = "AUV_INSIDE_TEST_NETNS"


def check_local(url: str, inside_netns: bool | None = None) -> str:
    """Return url if its traffic stays on this host, else raise ValueError."""
    if inside_netns is None:
        inside_netns = os.environ.get(NETNS_ENV) == "1"
    parsed = urlparse(url)
    if parsed.scheme != "udpm":
        return url  # memq://, file:// never touch the network
    ttl_values = parse_qs(parsed.query).get("ttl", ["0"])
    if not re.fullmatch(r"\d+", ttl_values[-1]):
        raise ValueError(f"{url}: ttl must be a number")
    ttl = int(ttl_values[-1])
    if ttl > 1 or (ttl == 1 and not inside_netns):
        raise ValueError(
            f"{url}: ttl={ttl} would send beyond this host; use ttl=0 "
            "(a TTL of 1 only inside a network namespace made for the run)"
        )
    return url


def with_receive_buffer(url: str, size: int = 4 << 20) -> str:
    """The URL with a large socket receive buffer: the logger must not drop
    messages when the machine is busy for a moment (the kernel caps the size
    at net.core.rmem_max)."""
    if not url.startswith("udpm://") or "recv_buf_size=" in url:
        return url
    return url + ("&" if "?" in url else "?") + f"recv_buf_size={size}"
