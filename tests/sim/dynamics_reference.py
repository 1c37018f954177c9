"""Writes data/dynamics_reference.json: what the dynamics computed on a fixed
set of states and inputs (right-hand side, one RK4 step, a few hundred
steps), for tests/sim/test_dynamics_reference.py, which also takes its
prepared() from here.

The committed file holds the figures of the Python implementation that the C
one (c/dynamics/) replaced: python/sim/dynamics.py at commit e8a9596, run as

    .venv/bin/python tests/sim/dynamics_reference.py --from-git e8a9596

which loads that file from git history into a throw-away module (nothing of it
stays in the tree). Without arguments it runs the current sim.dynamics and
prints how far it is from the committed figures; --write writes the current
figures instead (after a deliberate change to the equations: say why in the
commit).

Each case stores the vehicle's parameters in full (not as changes to the
defaults), so a later change of the default vehicle does not change the case.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

from sim.vehicle import REMUS100, VehicleParams

HERE = Path(__file__).resolve().parent
OUT = HERE / "data" / "dynamics_reference.json"
ROOT = HERE.parents[1]


def vehicle_dict(vp: VehicleParams) -> dict:
    return {
        "mass_kg": vp.mass_kg,
        "buoyancy_n": vp.buoyancy_n,
        "diameter_m": vp.diameter_m,
        "cg_m": list(vp.cg_m),
        "inertia_kgm2": list(vp.inertia_kgm2),
        "hydro": dict(vp.hydro),
    }


VEHICLES = {
    "remus100": vehicle_dict(REMUS100),
    # the CG off the centre line and off the CB's station, buoyancy below
    # weight: every xg/yg term and the other sign of the net weight
    "offset_cg": vehicle_dict(REMUS100.with_updates({"cg_m": (0.012, -0.006, 0.0196), "buoyancy_n": 290.0})),
}
R = REMUS100.radius_m
STILL = {"rudder": 0.0, "stern": 0.0, "thrust": 0.0, "torque": 0.0}


def case(name, x, vehicle="remus100", dt=0.02, steps=250, **inputs) -> dict:
    return {
        "name": name,
        "vehicle": vehicle,
        "dt": dt,
        "steps": steps,
        "x": list(map(float, x)),
        "inputs": {**STILL, **inputs},
    }


CASES = [
    case("still water, flying level", [0, 0, 10, 0, 0, 0, 1.5, 0, 0, 0, 0, 0], thrust=3.86, torque=-0.543),
    case("at rest, deep", [5, -3, 30, 0, 0, 1.0, 0, 0, 0, 0, 0, 0]),
    case(
        "every velocity, fins over, roll and pitch",
        [10, 20, 15, 0.3, -0.4, 2.0, 1.2, 0.15, -0.1, 0.2, -0.05, 0.12],
        rudder=0.2,
        stern=-0.15,
        thrust=3.0,
        torque=-0.42,
    ),
    case(
        "current",
        [0, 0, 12, 0.05, 0.1, 0.7, 1.4, -0.05, 0.03, 0.02, 0.04, -0.03],
        thrust=3.5,
        torque=-0.49,
        rudder=-0.05,
        current_ned=[0.3, -0.2, 0.02],
    ),
    case(
        "wave acceleration and current",
        [0, 0, 5, -0.08, 0.06, 4.0, 1.3, 0.02, -0.04, -0.03, 0.02, 0.05],
        thrust=3.2,
        torque=-0.45,
        stern=0.1,
        current_ned=[0.05, 0.1, -0.08],
        water_accel_ned=[0.12, -0.07, 0.25],
    ),
    case(
        "external forces",
        [0, 0, 20, 0.1, -0.1, 3.0, 0.8, 0.1, 0.05, 0.1, 0.1, -0.1],
        external_tau=[5.0, -3.0, 2.0, 0.4, -0.6, 0.8],
    ),
    case("near the surface, half out", [0, 0, 0.02, 0.05, 0.02, 0.5, 0.4, 0.0, 0.05, 0.0, 0.01, 0.0], thrust=1.0),
    case(
        "near the surface, waves",
        [0, 0, -0.5 * R, 0.0, -0.05, 1.5, 0.9, 0.01, -0.1, 0.05, -0.02, 0.01],
        water_accel_ned=[0.3, 0.1, -0.4],
        current_ned=[0.2, 0.0, 0.1],
    ),
    case("out of the water", [0, 0, -1.5 * R, 0.02, 0.0, 0.0, 0.5, 0, 0.2, 0, 0, 0], steps=20),
    case("surface exactly at the CB", [0, 0, 0.0, 0, 0, 0, 0, 0, 0, 0, 0, 0]),
    case("yaw wraps past 2 pi", [0, 0, 10, 0, 0, 2 * math.pi - 1e-3, 1.5, 0, 0, 0, 0, 0.3], steps=20, rudder=0.3),
    case("yaw wraps below 0", [0, 0, 10, 0, 0, 1e-3, 1.5, 0, 0, 0, 0, -0.3], steps=20, rudder=-0.3),
    case("roll wraps past pi", [0, 0, 10, math.pi - 1e-3, 0, 1.0, 0, 0, 0, 2.0, 0, 0], steps=20),
    case("roll wraps below -pi", [0, 0, 10, -math.pi + 1e-3, 0, 1.0, 0, 0, 0, -2.0, 0, 0], steps=20),
    case(
        "CG off the centre line, heavy, fine step",
        [1, 2, 8, 0.2, 0.3, 5.5, 1.0, -0.1, 0.1, -0.2, 0.1, 0.2],
        vehicle="offset_cg",
        dt=0.001,
        steps=500,
        rudder=0.1,
        stern=0.1,
        thrust=2.0,
        torque=-0.3,
        current_ned=[-0.1, 0.2, 0.0],
        water_accel_ned=[0.0, 0.05, 0.1],
        external_tau=[0.0, 1.0, 0.0, 0.0, 0.0, -0.2],
    ),
]
FRACTION_DEPTHS = [-2 * R, -R, -0.7 * R, -0.1 * R, 0.0, 0.3 * R, 0.99 * R, R, 3 * R]


def load_dynamics(rev: str | None):
    """sim.dynamics as it is now, or python/sim/dynamics.py at git revision rev."""
    if rev is None:
        import sim.dynamics

        return sim.dynamics
    src = subprocess.run(
        ["git", "show", f"{rev}:python/sim/dynamics.py"], cwd=ROOT, check=True, capture_output=True, text=True
    ).stdout
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
        f.write(src)
    spec = importlib.util.spec_from_file_location(f"dynamics_{rev}", f.name)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # dataclasses look their module up there
    spec.loader.exec_module(mod)
    Path(f.name).unlink()
    return mod


def prepared(dynamics_class, vehicles: dict, c: dict):
    """A Dynamics of the case's vehicle, state and inputs."""
    d = dynamics_class(VehicleParams().with_updates(vehicles[c["vehicle"]]), c["dt"])
    inp = c["inputs"]
    d.rudder, d.stern, d.thrust, d.torque = inp["rudder"], inp["stern"], inp["thrust"], inp["torque"]
    d.current_ned = tuple(inp.get("current_ned", (0.0, 0.0, 0.0)))
    d.water_accel_ned = tuple(inp.get("water_accel_ned", (0.0, 0.0, 0.0)))
    d.external_tau = inp.get("external_tau")
    d.set_state(c["x"][0:6], c["x"][6:12])
    return d


def run_case(dyn_mod, c: dict) -> dict:
    d = prepared(dyn_mod.Dynamics, VEHICLES, c)
    out = {"deriv": [float(v) for v in d._deriv(list(c["x"]))], "forces": d.forces()}
    d.step()
    out["x_1"], out["nu_dot_1"] = [float(v) for v in d.x[0:12]], [float(v) for v in d.nu_dot]
    for _ in range(c["steps"] - 1):
        d.step()
    out["x_n"], out["nu_dot_n"], out["t_n"] = [float(v) for v in d.x[0:12]], [float(v) for v in d.nu_dot], d.t
    return out


def compute(dyn_mod) -> dict:
    return {
        "vehicles": VEHICLES,
        "cases": [{**c, "expected": run_case(dyn_mod, c)} for c in CASES],
        "submerged_fraction": [[z, R, dyn_mod.submerged_fraction(z, R)] for z in FRACTION_DEPTHS],
    }


def worst_difference(a: dict, b: dict) -> tuple[float, str]:
    """The largest |a - b| / max(|b|, 1e-300) over every figure, and where."""
    worst, where = 0.0, ""
    for ca, cb in zip(a["cases"], b["cases"]):
        for key, vb in cb["expected"].items():
            va = ca["expected"][key]
            for i, (x, y) in enumerate(zip(va if isinstance(va, list) else [va], vb if isinstance(vb, list) else [vb])):
                rel = abs(x - y) / max(abs(y), 1e-300) if x != y else 0.0
                if rel > worst:
                    worst, where = rel, f"{cb['name']}: {key}[{i}] {x!r} vs {y!r}"
    for (_, _, x), (_, _, y) in zip(a["submerged_fraction"], b["submerged_fraction"]):
        rel = abs(x - y) / max(abs(y), 1e-300) if x != y else 0.0
        if rel > worst:
            worst, where = rel, f"submerged_fraction {x!r} vs {y!r}"
    return worst, where


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    how = ap.add_mutually_exclusive_group()
    how.add_argument("--from-git", metavar="REV", help="write the figures of python/sim/dynamics.py at REV")
    how.add_argument("--write", action="store_true", help="write the figures of the current sim.dynamics")
    args = ap.parse_args(argv)
    data = compute(load_dynamics(args.from_git))
    if args.from_git or args.write:
        how = f"--from-git {args.from_git}" if args.from_git else "--write"
        data = {"produced_by": f"tests/sim/dynamics_reference.py {how}", **data}
        # one line a case: small, and a diff shows which case changed
        lines = [f" {json.dumps(k)}: {json.dumps(v)}" for k, v in data.items() if k != "cases"]
        cases = ",\n  ".join(json.dumps(c) for c in data["cases"])
        OUT.write_text("{\n" + ",\n".join(lines) + ',\n "cases": [\n  ' + cases + "\n ]\n}\n")
        print(f"wrote {OUT} ({len(CASES)} cases)")
        return 0
    worst, where = worst_difference(data, json.loads(OUT.read_text()))
    print(f"largest relative difference from {OUT.name}: {worst:.3g}" + (f" ({where})" if where else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
