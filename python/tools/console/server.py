"""The console's web server: the page, a stream of updates, commands.

Standard library only. GET /api/events is a Server-Sent Events stream: each
page gets the model's "now" (serialised once per change for every page) plus
its own new trail points and contacts, at most `rate` times a second, and a
comment line every few seconds when nothing changes (so proxies keep it open).
POST /api/command publishes a mission command (live only); POST /api/seek
moves a log to a time (log only). Every request must name this console in
its Host header, and off loopback the stream and the commands need the login
token (tools/console/access.py); with a certificate it serves HTTPS.
"""

from __future__ import annotations

import json
import ssl
import threading
import time
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

from tools.console import plan_file
from tools.console.access import Access
from tools.console.mission_commands import COMMANDS
from tools.console.model import Model

STATIC = Path(__file__).resolve().parent / "static"
TYPES = {
    ".html": "text/html; charset=utf-8",
    ".js": "text/javascript; charset=utf-8",
    ".css": "text/css; charset=utf-8",
    ".png": "image/png",
}
KEEPALIVE_S = 5.0
MAX_BODY = 1 << 20  # a plan's text is a few kB; refuse anything silly
NEEDS_TOKEN = ("/api/events", "/api/command", "/api/seek")


class ConsoleServer(ThreadingHTTPServer):
    daemon_threads = True
    allow_reuse_address = True

    def __init__(
        self,
        address: tuple[str, int],
        model: Model,
        source: Any,
        rate_hz: float,
        access: Access | None = None,
        tls: ssl.SSLContext | None = None,
        plans: list[Path] | None = None,
    ) -> None:
        super().__init__(address, Handler)
        self.plans = list(plans or [])  # plan files shown to their author (plan_file.py)
        self.access = access or Access(address[0])
        self.tls = tls is not None
        if tls is not None:  # the handshake runs on the request's thread, not in accept()
            self.socket = tls.wrap_socket(self.socket, server_side=True, do_handshake_on_connect=False)
        self.model, self.source = model, source
        self.min_interval = 1.0 / max(rate_hz, 0.1)
        self.closing = threading.Event()
        self.pages = 0

    def info(self) -> dict[str, Any]:
        out = {"mode": self.source.mode, "commands": [c for c in COMMANDS if c != "start"]}
        if self.source.mode == "log":
            out.update(start=self.source.start_t, end=self.source.end_t, log=self.source.path.name)
        return out


class Handler(BaseHTTPRequestHandler):
    server: ConsoleServer
    protocol_version = "HTTP/1.1"

    def log_message(self, fmt: str, *args: Any) -> None:  # quiet: one line per page elsewhere
        pass

    # ------------------------------------------------------------- plumbing
    def _send(self, status: int, body: bytes, ctype: str = "application/json", cookie: str = "") -> None:
        self.send_response(status)
        if cookie:
            self.send_header("Set-Cookie", cookie)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        self.wfile.write(body)

    def _json(self, status: int, obj: Any) -> None:
        self._send(status, json.dumps(obj).encode())

    def _body(self) -> dict[str, Any] | None:
        try:
            n = int(self.headers.get("Content-Length", "0"))
        except ValueError:
            n = -1
        if not 0 <= n <= MAX_BODY:
            self._json(HTTPStatus.REQUEST_ENTITY_TOO_LARGE, {"error": "body missing or too large"})
            return None
        try:
            body = json.loads(self.rfile.read(n) or b"{}")
        except ValueError:
            body = None
        if not isinstance(body, dict):
            self._json(HTTPStatus.BAD_REQUEST, {"error": "the body must be a JSON object"})
            return None
        return body

    def _allowed(self) -> bool:
        """The Host header names this console (else 421), and a request that
        needs the login token carries it (else 401)."""
        acc = self.server.access
        if not acc.host_ok(self.headers.get("Host")):
            self._json(HTTPStatus.MISDIRECTED_REQUEST, {"error": "this console is not served under that host name"})
            return False
        path, _, query = self.path.partition("?")
        if path in NEEDS_TOKEN and not acc.token_ok(self.headers, query):
            self._json(HTTPStatus.UNAUTHORIZED, {"error": "login token needed: open the address the console printed"})
            return False
        return True

    # ------------------------------------------------------------- routes
    def do_GET(self) -> None:  # noqa: N802 (http.server's naming)
        if not self._allowed():
            return
        path, _, query = self.path.partition("?")
        login = path == "/" and self.server.access.token is not None and "token=" in query
        if login and not self.server.access.token_ok({}, query):
            self._json(HTTPStatus.UNAUTHORIZED, {"error": "wrong login token"})
            return
        if path == "/":
            path = "/static/index.html"
        if path.startswith("/static/"):
            name = path[len("/static/") :]
            file = (STATIC / name).resolve()
            if STATIC not in file.parents or not file.is_file() or file.suffix not in TYPES:
                self._json(HTTPStatus.NOT_FOUND, {"error": f"no {path}"})
                return
            cookie = self.server.access.cookie(self.server.tls) if login else ""
            self._send(HTTPStatus.OK, file.read_bytes(), TYPES[file.suffix], cookie)
        elif path == "/api/info":
            self._json(HTTPStatus.OK, self.server.info())
        elif path == "/api/plans":
            self._json(HTTPStatus.OK, [plan_file.describe(p) for p in self.server.plans])
        elif path == "/api/events":
            self._events()
        else:
            self._json(HTTPStatus.NOT_FOUND, {"error": f"no {path}"})

    def _same_origin_json(self) -> bool:
        """Commands only from the console's own page: another site open in the
        operator's browser could otherwise post to it. A JSON content type makes
        a cross-site request need a CORS preflight, which is never answered,
        and an Origin header, when sent, must name this server."""
        if self.headers.get("Content-Type", "").split(";")[0].strip() != "application/json":
            self._json(HTTPStatus.UNSUPPORTED_MEDIA_TYPE, {"error": "send application/json"})
            return False
        origin = self.headers.get("Origin")
        if origin is not None and urlparse(origin).netloc != self.headers.get("Host", ""):
            self._json(HTTPStatus.FORBIDDEN, {"error": f"not from this console's page ({origin})"})
            return False
        return True

    def do_POST(self) -> None:  # noqa: N802
        if not self._allowed() or not self._same_origin_json():
            return
        body = self._body()
        if body is None:
            return
        src = self.server.source
        if self.path == "/api/command":
            if src.mode != "live":
                self._json(HTTPStatus.CONFLICT, {"error": "a log cannot be commanded"})
                return
            vehicle, name = str(body.get("vehicle", "")), str(body.get("command", ""))
            if not vehicle or name not in COMMANDS:
                self._json(HTTPStatus.BAD_REQUEST, {"error": f"need a vehicle and a command ({', '.join(COMMANDS)})"})
                return
            try:
                seq = src.command(
                    vehicle,
                    str(body.get("manager", "")),
                    name,
                    str(body.get("plan_name", "")),
                    str(body.get("plan_text", "")),
                )
            except ValueError as exc:
                self._json(HTTPStatus.BAD_REQUEST, {"error": str(exc)})
                return
            print(
                f"console: {name} sent to {vehicle} {body.get('manager') or '(every manager)'}, seq {seq}", flush=True
            )
            self._json(HTTPStatus.OK, {"seq": seq})
        elif self.path == "/api/seek":
            if src.mode != "log":
                self._json(HTTPStatus.CONFLICT, {"error": "live data cannot be seeked"})
                return
            try:
                t = float(body.get("t", 0.0))
            except (TypeError, ValueError):
                self._json(HTTPStatus.BAD_REQUEST, {"error": "t must be a number"})
                return
            self._json(HTTPStatus.OK, {"t": src.seek(t)})
        else:
            self._json(HTTPStatus.NOT_FOUND, {"error": f"no {self.path}"})

    def _events(self) -> None:
        self.send_response(HTTPStatus.OK)
        self.send_header("Content-Type", "text/event-stream")
        self.send_header("Cache-Control", "no-store")
        self.send_header("Connection", "close")
        self.end_headers()
        self.close_connection = True
        srv, model = self.server, self.server.model
        cursors: dict[str, int] = {}
        epoch = version = world_version = structures_version = -1
        sent_plans: dict[str, str] = {}  # the structures this page has: key -> plan_id
        srv.pages += 1
        try:
            while not srv.closing.is_set():
                began = time.monotonic()
                with model.lock:
                    model.lock.wait_for(lambda: model.version != version or srv.closing.is_set(), timeout=KEEPALIVE_S)
                    if model.version == version:
                        chunk = b": keepalive\n\n"
                    else:
                        fresh = model.epoch != epoch
                        if fresh:
                            sent_plans.clear()
                            structures_version = -1
                        epoch = model.epoch
                        series = model.series_since(cursors, fresh)
                        parts = ['{"now":', model.now_json(), ',"series":', json.dumps(series, separators=(",", ":"))]
                        if model.world_version != world_version:
                            parts += [',"world":', json.dumps(model.world, separators=(",", ":"))]
                            world_version = model.world_version
                        if model.structures_version != structures_version:
                            plans = model.structures_since(sent_plans)
                            if plans:
                                parts += [',"structures":', json.dumps(plans, separators=(",", ":"))]
                            structures_version = model.structures_version
                        parts.append("}")
                        version = model.version
                        chunk = ("data: " + "".join(parts) + "\n\n").encode()
                self.wfile.write(chunk)
                self.wfile.flush()
                rest = srv.min_interval - (time.monotonic() - began)
                if rest > 0:
                    srv.closing.wait(rest)
        except (BrokenPipeError, ConnectionResetError, TimeoutError):
            pass
        finally:
            srv.pages -= 1
