"""One builder per program's command line: chasm-manager, auv-nav, auv-front-estimate, the simulator,
the recorders, the device drivers and their replay.

Every process that starts one of these (the launcher, the host agents through the
launcher's core, the multi-HIL world, tests, benchmarks) builds its command here,
so a flag is spelled in one place. The LCM URL is `--lcm-url` for every program
of the project, as LCM's own tools spell it (lcm-logger, lcm-logplayer, lcm-spy);
`add_lcm_url_argument` gives the Python command lines the same flag.

`build` is a build tree (`build/`, or `build/san/` for the sanitized programs).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Iterable, Mapping
from pathlib import Path

from auvlcm.url import with_receive_buffer

PathLike = str | Path


def chasm_manager(
    build: Path,
    *,
    plan: PathLike,
    bind: PathLike,
    vehicle: str,
    name: str,
    lcm_url: str,
    rate_hz: float = 10.0,
    status_rate_hz: float | None = None,
    clock: str = "sim",
    plugin_path: Iterable[PathLike] = (),
    params: Mapping[str, object] | None = None,
    key_file: PathLike | None = None,
    extra: Iterable[PathLike] = (),
) -> list[str]:
    """A manager running `plan` with `bind` as `<vehicle>`'s `<name>` on the given
    clock (`sim`: SIM.CLOCK; `system`: this machine's); with `key_file` it takes
    only signed commands (docs/security.md)."""
    cmd = [str(build / "bin" / "chasm-manager"), "--plan", str(plan), "--bind", str(bind)]
    cmd += ["--vehicle", vehicle, "--name", name, "--rate", f"{rate_hz:g}"]
    if status_rate_hz is not None:
        cmd += ["--status-rate", f"{status_rate_hz:g}"]
    cmd += ["--clock", clock, "--lcm-url", lcm_url]
    for d in plugin_path:
        cmd += ["--plugin-path", str(d)]
    for k, v in (params or {}).items():
        cmd += ["-D", f"{k}={v}"]
    if key_file:
        cmd += ["--key-file", str(key_file)]
    return cmd + [str(x) for x in extra]


def auv_nav(
    build: Path,
    *,
    config: PathLike,
    vehicle: str,
    lcm_url: str,
    rate_hz: float | None = None,
    clock: str = "sim",
    extra: Iterable[PathLike] = (),
) -> list[str]:
    """The onboard navigation filter of `vehicle` with its nav config."""
    cmd = [str(build / "bin" / "auv-nav"), "--config", str(config), "--vehicle", vehicle]
    if rate_hz is not None:
        cmd += ["--rate", f"{rate_hz:g}"]
    return cmd + ["--clock", clock, "--lcm-url", lcm_url] + [str(x) for x in extra]


def auv_front_estimate(
    build: Path,
    *,
    vehicle: str,
    lcm_url: str,
    rate_hz: float | None = None,
    clock: str = "sim",
    max_age_s: float | None = None,
    max_depth_m: float | None = None,
    extra: Iterable[PathLike] = (),
) -> list[str]:
    """The on-board front estimator of `vehicle` (c/frontest, docs/sampling.md): its
    CTD at its navigated positions in, front_estimate_t on <vehicle>.FRONT_ESTIMATE
    at `rate_hz` of mission time out; readings older than `max_age_s` or deeper
    than `max_depth_m` are not fitted."""
    cmd = [str(build / "bin" / "auv-front-estimate"), "--vehicle", vehicle]
    for flag, value in (("--rate", rate_hz), ("--max-age", max_age_s), ("--max-depth", max_depth_m)):
        if value is not None:
            cmd += [flag, f"{value:g}"]
    return cmd + ["--clock", clock, "--lcm-url", lcm_url] + [str(x) for x in extra]


def simulator(
    config: PathLike,
    *,
    lcm_url: str,
    clock: str | None = None,
    warp: float | None = None,
    duration: float | None = None,
    python: PathLike = sys.executable,
    extra: Iterable[PathLike] = (),
) -> list[str]:
    """One vehicle's simulator (`python -m sim`); the clock, warp and duration
    override its configuration's when given."""
    cmd = [str(python), "-m", "sim", str(config), "--lcm-url", lcm_url]
    if clock is not None:
        cmd += ["--clock", clock]
    if warp is not None:
        cmd += ["--warp", f"{warp:g}"]
    if duration is not None:
        cmd += ["--duration", f"{duration:g}"]
    return cmd + [str(x) for x in extra]


def radio_sim(
    *,
    vehicles: Iterable[str],
    lcm_url: str,
    clock: str = "sim",
    settings: Mapping[str, object] | None = None,
    pipes: Mapping[str, PathLike] | None = None,
    lockstep_name: str | None = None,
    shore_lcm_url: str | None = None,
    python: PathLike = sys.executable,
) -> list[str]:
    """The simulated surface radio (`python -m sim.radio`, docs/radio.md); settings:
    sim.radio.link.RadioConfig's fields, each a flag (bitrate_bps -> --bitrate-bps);
    pipes: the vehicles whose radio is a byte pipe, a pty at that path (auv-radio's port);
    lockstep_name: it takes part in a lockstep world under that name; shore_lcm_url: the
    shore's own LCM (its gateway's and tools')."""
    cmd = [str(python), "-m", "sim.radio", "--vehicles", ",".join(vehicles), "--clock", clock, "--lcm-url", lcm_url]
    for k, v in (settings or {}).items():
        cmd += ["--" + k.replace("_", "-"), f"{v:g}" if isinstance(v, float) else str(v)]
    if pipes:
        cmd += ["--pipe", ",".join(f"{n}={p}" for n, p in pipes.items())]
    if lockstep_name:
        cmd += ["--lockstep-name", lockstep_name]
    if shore_lcm_url:
        cmd += ["--shore-lcm-url", shore_lcm_url]
    return cmd


def radio_shore(
    *,
    vehicles: Iterable[str],
    lcm_url: str,
    clock: str = "sim",
    acoustic: Mapping[str, int] | None = None,
    link_timeout_s: float | None = None,
    retry_s: float | None = None,
    key_file: PathLike | None = None,
    python: PathLike = sys.executable,
) -> list[str]:
    """The shore radio gateway (docs/radio.md); acoustic: team index per vehicle;
    key_file: the team keys its acoustic commands are tagged with (docs/security.md)."""
    cmd = [str(python), "-m", "tools.radio.shore_gateway", "--vehicles", ",".join(vehicles), "--clock", clock]
    if acoustic:
        cmd += ["--acoustic", ",".join(f"{v}={i}" for v, i in acoustic.items())]
    if link_timeout_s is not None:
        cmd += ["--link-timeout-s", f"{link_timeout_s:g}"]
    if retry_s is not None:
        cmd += ["--retry-s", f"{retry_s:g}"]
    if key_file is not None:
        cmd += ["--key-file", str(key_file)]
    return cmd + ["--lcm-url", lcm_url]


def radio_vehicle(
    build: Path,
    *,
    vehicle: str,
    spool: PathLike,
    lcm_url: str,
    port: PathLike | None = None,
    tcp: str | None = None,
    clock: str = "sim",
    team_index: int | None = None,
    report_period_s: float | None = None,
    end_manager: str | None = None,
    key_file: PathLike | None = None,
    peers: Iterable[str] = (),
    raw: bool = False,
) -> list[str]:
    """A vehicle's radio gateway, `auv-radio` (c/drivers/radio, docs/radio.md), on the
    radio modem's serial `port` (the simulated radio's pty) or `tcp` "HOST:PORT";
    spool: its partial transfers; key_file: the team keys acoustic commands are
    verified with and the managers' commands signed; peers: the teammates its status also
    goes to (and whose status it publishes)."""
    extra: list[PathLike] = ["--spool", str(spool)]
    if peers:
        extra += ["--peers", ",".join(peers)]
    if team_index is not None:
        extra += ["--team-index", str(team_index)]
    if report_period_s is not None:
        extra += ["--report-period-s", f"{report_period_s:g}"]
    if end_manager is not None:
        extra += ["--end-manager", end_manager]
    if key_file is not None:
        extra += ["--key-file", str(key_file)]
    return device_driver(
        build, "radio", vehicle=vehicle, lcm_url=lcm_url, port=port, tcp=tcp, raw=raw, clock=clock, extra=extra
    )


def auv_recorder(build: Path, *, lcm_url: str, log: PathLike, stats: PathLike | None = None) -> list[str]:
    """auv-recorder (c/recorder), with a large receive buffer; its counts go to
    `stats` at exit."""
    cmd = [str(build / "bin" / "auv-recorder"), "--lcm-url", with_receive_buffer(lcm_url), "-f", str(log)]
    return cmd + (["--stats", str(stats)] if stats is not None else [])


def lcm_logger(lcm_bin: Path, *, lcm_url: str, log: PathLike) -> list[str]:
    """LCM's own lcm-logger (its binary in the wheel, not its Python wrapper, so
    a signal reaches the logger itself), with a large receive buffer."""
    url = with_receive_buffer(lcm_url)
    return [str(lcm_bin / "lcm-logger"), f"--lcm-url={url}", "--quiet", "--flush-interval=100", "-f", str(log)]


def device_driver(
    build: Path,
    device: str,
    *,
    vehicle: str,
    lcm_url: str,
    port: PathLike | None = None,
    baud: int | None = None,
    tcp: str | None = None,
    raw: bool = False,
    clock: str = "system",
    extra: Iterable[PathLike] = (),
) -> list[str]:
    """A device driver `auv-<device>` (c/drivers/<device>, docs/drivers.md) on a
    serial `port` (at `baud`) or a TCP `tcp` "HOST:PORT"; `raw` records its
    bytes on <vehicle>.RAW.<DEVICE>; `extra` are the driver's own flags."""
    if (port is None) == (tcp is None):
        raise ValueError("a driver takes one of port and tcp")
    cmd = [str(build / "bin" / f"auv-{device}")]
    cmd += ["--device", str(port)] if port is not None else ["--tcp", tcp]
    if baud is not None:
        cmd += ["--baud", str(int(baud))]
    cmd += ["--vehicle", vehicle, "--lcm-url", lcm_url, "--clock", clock]
    if raw:
        cmd.append("--raw")
    return cmd + [str(x) for x in extra]


def gps_origin_flags(lat0_deg: float, lon0_deg: float) -> list[str]:
    """auv-gps's --origin: the world's local frame (python/sim/geo.py's origin)."""
    return ["--origin", f"{lat0_deg:.10f},{lon0_deg:.10f}"]


def dvl_flags(
    *,
    mounting_deg: tuple[float, float, float] | None = None,
    sigma_mps: float | None = None,
    ensemble_timeout_s: float | None = None,
) -> list[str]:
    """auv-dvl's own flags: the DVL's yaw, pitch, roll from the body [deg], the
    published velocity sigma, and the silence that drops a cut ensemble."""
    cmd: list[str] = []
    if mounting_deg is not None:
        cmd += ["--mounting", ",".join(f"{float(a):.6f}" for a in mounting_deg)]
    if sigma_mps is not None:
        cmd += ["--sigma", f"{float(sigma_mps):g}"]
    if ensemble_timeout_s is not None:
        cmd += ["--ensemble-timeout", f"{float(ensemble_timeout_s):g}"]
    return cmd


def servo_table_flags(table: PathLike) -> list[str]:
    """auv-servo's --table: the fins-and-thruster channel table (docs/drivers.md, "auv-servo")."""
    return ["--table", str(table)]


def frontseat(
    build: Path,
    *,
    vehicle: str,
    lcm_url: str,
    port: PathLike | None = None,
    baud: int | None = None,
    tcp: str | None = None,
    protocol: str = "iver3",
    origin: tuple[float, float] | None = None,
    max_depth_m: float | None = None,
    min_speed_mps: float | None = None,
    max_speed_mps: float | None = None,
    helm_version: int | None = None,
    silent_after_s: float | None = None,
    setpoint_timeout_s: float | None = None,
    raw: bool = False,
    clock: str = "system",
) -> list[str]:
    """auv-frontseat (c/frontseat, docs/frontseat.md): a commercial vehicle's frontseat
    on a serial `port` or a TCP `tcp`, standing where the PILOT stands: the vehicle's
    limits (setpoints beyond them clamped or refused), the world's `origin` for NAV's
    north and east, the frontseat software's `helm_version`."""
    extra: list[str] = ["--protocol", protocol]
    if origin is not None:
        extra += gps_origin_flags(*origin)
    for flag, value in (
        ("--max-depth", max_depth_m),
        ("--min-speed", min_speed_mps),
        ("--max-speed", max_speed_mps),
        ("--silent-after", silent_after_s),
        ("--setpoint-timeout", setpoint_timeout_s),
    ):
        if value is not None:
            extra += [flag, f"{value:g}"]
    if helm_version is not None:
        extra += ["--helm-version", str(int(helm_version))]
    return device_driver(
        build,
        "frontseat",
        vehicle=vehicle,
        lcm_url=lcm_url,
        port=port,
        baud=baud,
        tcp=tcp,
        raw=raw,
        clock=clock,
        extra=extra,
    )


def modem_flags(
    table: dict[str, int],
    *,
    rate: int | None = None,
    ack: bool = False,
    cst: bool = True,
    kind: int | None = None,
    answer_timeout_s: float | None = None,
    ack_timeout_s: float | None = None,
    rx_hold_s: float | None = None,
) -> list[str]:
    """auv-modem's own flags (docs/drivers.md, "auv-modem"): the address table
    (vehicle id -> modem address, the same on every vehicle), the rate frames
    are sent at, acks, CACST, the kind the link carries and its timeouts [s]."""
    cmd = ["--table", ",".join(f"{v}={int(a)}" for v, a in table.items())]
    if rate is not None:
        cmd += ["--rate", str(int(rate))]
    if ack:
        cmd.append("--ack")
    if not cst:
        cmd.append("--no-cst")
    if kind is not None:
        cmd += ["--kind", str(int(kind))]
    for flag, v in (("--answer-timeout", answer_timeout_s), ("--ack-timeout", ack_timeout_s), ("--rx-hold", rx_hold_s)):
        if v is not None:
            cmd += [flag, f"{float(v):g}"]
    return cmd


def payload_flags(*, frame_timeout_s: float | None = None) -> list[str]:
    """auv-payload's own flag: the silence that drops a frame cut short [s]."""
    return [] if frame_timeout_s is None else ["--frame-timeout", f"{frame_timeout_s:g}"]


def driver_replay(
    build: Path,
    *,
    log: PathLike,
    vehicle: str,
    device: str,
    lcm_url: str | None = None,
    extra: Iterable[PathLike] = (),
) -> list[str]:
    """auv-driver-replay: a log's <vehicle>.RAW.<DEVICE> bytes through the
    driver's parser again, published on `lcm_url`, or printed when it is None."""
    cmd = [str(build / "bin" / "auv-driver-replay"), str(log), "--vehicle", vehicle, "--device", device]
    cmd += ["--lcm-url", lcm_url] if lcm_url is not None else ["--print"]
    return cmd + [str(x) for x in extra]


class _OldUrlSpelling(argparse.Action):
    """`--url`, the old spelling: still understood, with a note once."""

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"{parser.prog}: --url is now spelled --lcm-url", file=sys.stderr)
        setattr(namespace, self.dest, values)


def add_lcm_url_argument(ap: argparse.ArgumentParser, help: str, **kwargs) -> None:
    """The LCM URL option of a Python command: `--lcm-url` into `args.url`."""
    ap.add_argument("--lcm-url", dest="url", metavar="URL", help=help, **kwargs)
    ap.add_argument("--url", dest="url", action=_OldUrlSpelling, help=argparse.SUPPRESS)
