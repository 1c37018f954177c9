"""Command line: `python -m sim CONFIG.yaml [options]`, `python -m sim validate`."""

from __future__ import annotations

import argparse
import sys

from sim import clock_modes


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "validate":
        from sim.validate import main as vmain

        return vmain(argv[1:])
    ap = argparse.ArgumentParser(
        prog="python -m sim",
        description="CHASM-AUV vehicle simulator (one vehicle, over LCM). "
        "`python -m sim.validate` (or `python -m sim validate`) prints the validation report.",
    )
    ap.add_argument("config", help="simulator configuration (YAML), e.g. missions/sim/remus100.yaml")
    ap.add_argument(
        "--clock",
        type=clock_modes.argument,
        metavar="{realtime,scaled,lockstep}",
        help="override simulation.clock (`stepped`, its old name, is read as lockstep)",
    )
    ap.add_argument("--warp", type=float, help="override simulation.warp (scaled mode)")
    ap.add_argument("--fast", action="store_true", help="scaled mode as fast as the CPU allows")
    ap.add_argument("--duration", type=float, help="stop after this many sim seconds")
    ap.add_argument("--lcm-url", help="override simulation.lcm_url (ttl=0 only)")
    ap.add_argument("--check", action="store_true", help="check the configuration and exit")
    ap.add_argument("--multihil", action="store_true", help="join a shared world (docs/multihil.md)")
    ap.add_argument("--priority", type=int, help="override multihil.priority")
    ap.add_argument("--clock-offset-us", type=float, help="multi-HIL tests: offset this clock")
    ap.add_argument("--clock-drift-ppm", type=float, help="multi-HIL tests: drift this clock")
    args = ap.parse_args(argv)

    from sim.config import load_or_report

    cfg = load_or_report(args.config)
    if cfg is None:
        return 2
    if args.clock:
        cfg.sim.clock = args.clock
    if args.warp is not None:
        if not 0 < args.warp < float("inf"):
            ap.error("--warp must be > 0")
        cfg.sim.warp = args.warp
    if args.fast:
        cfg.sim.clock = "scaled"
    if args.duration is not None:
        cfg.sim.duration_s = args.duration
    if args.lcm_url:
        cfg.sim.lcm_url = args.lcm_url
    from sim.multihil.hook import apply_cli

    apply_cli(cfg, args)
    if args.check:
        print(f"{args.config}: ok (vehicle {cfg.vehicle_id}, {len(cfg.sensors)} sensors configured)")
        return 0
    from sim.hil import Simulator

    try:
        sim = Simulator(cfg, fast=args.fast)
    except ValueError as exc:
        print(f"sim: {exc}", file=sys.stderr)
        return 2
    return sim.run()


if __name__ == "__main__":
    sys.exit(main())
