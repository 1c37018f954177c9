"""Who may use the console's HTTP side (tools/console/access.py), on a real
server in this process: a Host header it is not served under is refused
(DNS rebinding: 421); off loopback the event stream and commands need the
login token (bearer, cookie from the printed address, never a wrong one);
with a certificate it speaks TLS and only TLS."""

from __future__ import annotations

import http.client
import json
import shutil
import ssl
import subprocess
import threading

import pytest

from tools.console.access import Access
from tools.console.model import Model
from tools.console.server import ConsoleServer


class FakeSource:
    mode = "live"

    def __init__(self) -> None:
        self.sent: list[tuple] = []

    def command(self, vehicle, manager, name, plan_name="", plan_text="") -> int:
        self.sent.append((vehicle, name))
        return len(self.sent)


def serve(access: Access, tls: ssl.SSLContext | None = None):
    src = FakeSource()
    srv = ConsoleServer(("127.0.0.1", 0), Model(), src, 5.0, access, tls)
    threading.Thread(target=srv.serve_forever, kwargs={"poll_interval": 0.05}, daemon=True).start()
    return srv, src


def request(srv, method: str, path: str, host: str | None = None, body=None, headers=None, tls=None):
    port = srv.server_address[1]
    conn = (
        http.client.HTTPSConnection("127.0.0.1", port, context=tls, timeout=10)
        if tls
        else http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    )
    h = {"Host": host if host is not None else f"127.0.0.1:{port}", **(headers or {})}
    data = None
    if body is not None:
        data, h["Content-Type"] = json.dumps(body).encode(), "application/json"
    conn.request(method, path, body=data, headers=h)
    r = conn.getresponse()
    out = (r.status, dict(r.getheaders()), r.read(200) if path != "/api/events" else r.read(20))
    conn.close()
    return out


def stop(srv) -> None:
    srv.closing.set()
    srv.shutdown()
    srv.server_close()


def test_host_header_and_login_token():
    srv, src = serve(Access("0.0.0.0", "s3cret-token-of-24-chars", ("console.ship.lan",)))
    try:
        port = srv.server_address[1]
        assert request(srv, "GET", "/api/info", host=f"evil.example:{port}")[0] == 421  # rebinding
        assert request(srv, "GET", "/api/info", host="")[0] == 421
        for ok in (f"127.0.0.1:{port}", "localhost", f"console.ship.lan:{port}", f"[::1]:{port}", "10.0.0.7"):
            assert request(srv, "GET", "/api/info", host=ok)[0] == 200, ok
        cmd = {"vehicle": "AUV1", "command": "pause"}
        assert request(srv, "POST", "/api/command", body=cmd)[0] == 401
        assert request(srv, "GET", "/api/events")[0] == 401
        assert request(srv, "GET", "/?token=wrong-token-wrong-token")[0] == 401
        status, headers, _ = request(srv, "GET", "/?token=s3cret-token-of-24-chars")
        cookie = headers["Set-Cookie"]
        assert status == 200 and "HttpOnly" in cookie and "SameSite=Strict" in cookie and "Secure" not in cookie
        assert request(srv, "POST", "/api/command", body=cmd, headers={"Cookie": cookie.split(";")[0]})[0] == 200
        bearer = {"Authorization": "Bearer s3cret-token-of-24-chars"}
        assert request(srv, "GET", "/api/events", headers=bearer)[0] == 200
        assert request(srv, "POST", "/api/command", body=cmd, headers={"Authorization": "Bearer nope"})[0] == 401
        assert src.sent == [("AUV1", "pause")]
    finally:
        stop(srv)
    assert Access("127.0.0.1").token is None and len(Access("0.0.0.0").token or "") >= 24


@pytest.mark.skipif(shutil.which("openssl") is None, reason="the openssl command makes the test certificate")
def test_tls_with_a_certificate(tmp_path):
    cert, key = tmp_path / "cert.pem", tmp_path / "key.pem"
    subprocess.run(
        ["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1", "-subj", "/CN=localhost"]
        + ["-addext", "subjectAltName=IP:127.0.0.1", "-keyout", str(key), "-out", str(cert)],
        check=True,
        capture_output=True,
    )
    ctx = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
    ctx.load_cert_chain(cert, key)
    srv, _ = serve(Access("127.0.0.1"), ctx)
    try:
        client = ssl.create_default_context(cafile=str(cert))
        status, _, body = request(srv, "GET", "/api/info", tls=client)
        assert status == 200 and b'"mode": "live"' in body
        with pytest.raises((http.client.HTTPException, ConnectionError, OSError)):
            request(srv, "GET", "/api/info")  # plain HTTP to the TLS port
    finally:
        stop(srv)
