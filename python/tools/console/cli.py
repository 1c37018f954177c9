#!/usr/bin/env python3
"""The operator's console: a live map in the browser (docs/console.md).

    auv-console [--lcm-url URL] [--bind ADDR] [--port N] [--scenario FILE]   live LCM (or lcm-logplayer)
    auv-console --log RUN.lcmlog [--bind ADDR] [--port N]                 a finished log, with a time slider
    auv-console ... --plan FILE.chasm                                       a plan file for its author, not run

Serves a page with the vehicles (heading, true and navigation trails), the
survey area, lines and operating area, the seabed, contacts, targets and modem
frames; per vehicle each manager's state, navigation quality and modem
counters; and pause / resume / abort / load-plan buttons that send
MISSION_CMD and show the acknowledgement. Everything it serves is in the
repository: no internet needed. It binds to localhost unless told otherwise
(`--bind 0.0.0.0` for every interface of the operator's network).

Exit status: 0 on Ctrl-C or SIGTERM, 2 on a usage, file or address error.
"""

from __future__ import annotations

import argparse
import signal
import ssl
import sys
from pathlib import Path

from auvlcm import auth, programs
from auvlcm.url import check_local, default_url
from tools.console.access import Access, read_token
from tools.console.model import Model
from tools.console.server import ConsoleServer
from tools.console.sources import LiveSource, LogSource
from tools.console.world import WorldBuilder, WorldError


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="auv-console", description=__doc__.split("\n\n")[0])
    programs.add_lcm_url_argument(ap, "LCM URL (default $LCM_DEFAULT_URL or the project's)", default=None)
    ap.add_argument("--bind", default="127.0.0.1", help="address to serve on (default 127.0.0.1)")
    ap.add_argument("--port", type=int, default=8770, help="port (default 8770; 0 picks a free one)")
    ap.add_argument("--scenario", type=Path, help="scenario YAML: survey, seabed and LBL net from the start")
    ap.add_argument("--log", type=Path, help="open a finished log instead of live LCM")
    ap.add_argument(
        "--plan", type=Path, action="append", default=[], help="a plan file to show its author (tree, errors, checks)"
    )
    ap.add_argument("--rate", type=float, default=5.0, help="page updates per second at most (default 5)")
    auth.add_key_file_argument(ap)
    ap.add_argument(
        "--token-file", type=Path, help="login token (first line, mode 0600) off loopback; default: a new one"
    )
    ap.add_argument("--allow-host", action="append", default=[], help="a host name the console is reached by (repeat)")
    ap.add_argument("--tls-cert", type=Path, help="PEM certificate: serve HTTPS (with --tls-key)")
    ap.add_argument("--tls-key", type=Path, help="PEM private key of --tls-cert")
    ap.add_argument(
        "--shore", action="store_true", help="send commands through the radio's shore gateway (SHORE.<V>.MISSION_CMD)"
    )
    args = ap.parse_args(argv)

    model = Model()
    world = WorldBuilder(model)
    try:
        if args.scenario is not None:
            world.load_scenario(args.scenario)
        if args.log is not None:
            if not args.log.is_file():
                raise WorldError(f"{args.log}: no such log")
            source = LogSource(model, world, args.log)
            where = f"log {args.log} ({source.end_t - source.start_t:.0f} s of sim time)"
        else:
            url = check_local(args.url or default_url())
            source = LiveSource(
                model, world, url, auth.ring_for(args.key_file, "console"), "SHORE." if args.shore else ""
            )
            where = f"live on {url}"
        token = read_token(args.token_file) if args.token_file else None
        access = Access(args.bind, token, tuple(args.allow_host))
        tls = None
        if args.tls_cert or args.tls_key:
            if not (args.tls_cert and args.tls_key):
                raise ValueError("--tls-cert and --tls-key go together")
            tls = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
            tls.load_cert_chain(args.tls_cert, args.tls_key)
    except (WorldError, ValueError, OSError, ssl.SSLError) as exc:
        print(f"console: {exc}", file=sys.stderr)
        return 2
    try:
        server = ConsoleServer((args.bind, args.port), model, source, args.rate, access, tls, plans=args.plan)
    except OSError as exc:
        print(f"console: cannot serve on {args.bind}:{args.port}: {exc.strerror or exc}", file=sys.stderr)
        return 2

    def stop(signum, frame):  # noqa: ARG001
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    source.start()
    host, port = server.server_address[:2]
    scheme = "https" if tls else "http"
    login = f"?token={access.token}" if access.token else ""
    print(f"console: serving {scheme}://{host}:{port}/{login} ({where})", flush=True)
    try:
        server.serve_forever(poll_interval=0.2)
    except KeyboardInterrupt:
        pass
    finally:
        server.closing.set()
        with model.lock:
            model.lock.notify_all()
        server.server_close()
        source.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
