"""Who may use the console's HTTP side (docs/console.md, "Access").

- Host header: only names the console is served under. A web page of another
  site can make the operator's browser resolve its own name to this console's
  address (DNS rebinding) and then read and command it as same-origin; its
  requests then carry its own name in Host, so anything but an IP address,
  localhost, this machine's name or an --allow-host name is refused (421).
- Login token: on any address but loopback, the event stream and every command
  need the token (printed at start, or read from --token-file). The page gets it
  once in its address (`/?token=...`), which sets an HttpOnly, SameSite=Strict
  cookie; tools may send `Authorization: Bearer TOKEN` instead.
"""

from __future__ import annotations

import hmac
import ipaddress
import secrets
import socket
from pathlib import Path

COOKIE = "console_token"


def is_loopback(addr: str) -> bool:
    try:
        return ipaddress.ip_address(addr).is_loopback
    except ValueError:
        return addr == "localhost"


def read_token(path: Path) -> str:
    """The first line of a token file; ValueError when it is empty or open to others."""
    if path.stat().st_mode & 0o077:
        raise ValueError(f"{path}: token file open to group or others: chmod 600 it")
    token = path.read_text().strip().splitlines()[0].strip() if path.read_text().strip() else ""
    if len(token) < 16:
        raise ValueError(f"{path}: a token of at least 16 characters, on its first line")
    return token


class Access:
    def __init__(self, bind: str, token: str | None = None, allow_hosts: tuple[str, ...] = ()) -> None:
        self.names = {"localhost", socket.gethostname().lower(), socket.getfqdn().lower(), *map(str.lower, allow_hosts)}
        self.token = None if is_loopback(bind) else (token or secrets.token_urlsafe(24))

    def host_ok(self, host_header: str | None) -> bool:
        """Whether Host names this console: an IP literal, or one of its names (any port)."""
        if not host_header:
            return False
        host = host_header.strip().lower()
        if host.startswith("["):  # [v6]:port
            host = host[1 : host.find("]")] if "]" in host else ""
        elif host.count(":") == 1:
            host = host.split(":")[0]
        try:
            ipaddress.ip_address(host)
            return True
        except ValueError:
            return host.rstrip(".") in self.names

    def token_ok(self, headers, query: str) -> bool:
        """No token needed, or the request carries it (cookie, bearer or ?token=)."""
        if self.token is None:
            return True
        offered = []
        auth = headers.get("Authorization", "")
        if auth.startswith("Bearer "):
            offered.append(auth[len("Bearer ") :].strip())
        for part in headers.get("Cookie", "").split(";"):
            k, _, v = part.strip().partition("=")
            if k == COOKIE:
                offered.append(v)
        for part in query.split("&"):
            k, _, v = part.partition("=")
            if k == "token":
                offered.append(v)
        return any(hmac.compare_digest(o.encode(), self.token.encode()) for o in offered)

    def cookie(self, tls: bool) -> str:
        assert self.token is not None
        return f"{COOKIE}={self.token}; HttpOnly; SameSite=Strict; Path=/" + ("; Secure" if tls else "")
