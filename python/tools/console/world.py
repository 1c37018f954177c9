"""The map's fixed layers: survey area and lines, operating area, LBL net, seabed,
and the water's temperature where the world has an ocean.

They come from wherever they are known, the latest source winning: a scenario
file given on the command line, the log's own annotations (the planner's
survey.json, each simulator's merged configuration) and SIM.ENV (the seabed
reference, the transponders and the ocean the environment server serves).

The water layer is the world's temperature at WATER_DEPTH_M (the upper water a
sampling team maps, docs/sampling.md) at the world's start, over the area of the
other layers and the vehicles' starts: a front that moves, or a plume the current
carries, is drawn where it was at t = 0 (the report's `front_field` plot has it
at the mission's end).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import yaml

from tools.console.model import Model

GRID = 40  # seabed cells per side sent to the page
WATER_GRID = 64  # water cells per side: a front is a few cells wide
WATER_DEPTH_M = 5.0


class WorldError(ValueError):
    pass


class WorldBuilder:
    def __init__(self, model: Model) -> None:
        self.model = model
        self.survey: dict[str, Any] | None = None
        self.bathymetry_ref = ""
        self.base_dir = Path.cwd()
        self.transponders: list[dict[str, float]] = []
        self.name = ""
        self.ocean: Any = None  # sim.ocean.fields.Ocean of the world, if it has one
        self.starts: dict[str, tuple[float, float]] = {}  # vehicle -> (north, east) at the start

    # ------------------------------------------------------------- sources
    def load_scenario(self, path: Path) -> None:
        """A launcher scenario: its world (seabed, transponders) and its survey.json."""
        try:
            doc = yaml.safe_load(path.read_text())
        except (OSError, yaml.YAMLError) as exc:
            raise WorldError(f"{path}: cannot read the scenario ({exc})") from None
        if not isinstance(doc, dict):
            raise WorldError(f"{path}:1:1: a scenario is a mapping")
        world = doc.get("world") or {}
        if isinstance(world, str):  # a world file next to the scenario
            try:
                world = yaml.safe_load((path.parent / world).read_text()) or {}
            except (OSError, yaml.YAMLError) as exc:
                raise WorldError(f"{path}: cannot read its world {world} ({exc})") from None
        self.name = str(doc.get("name", path.stem))
        self.base_dir = path.parent
        if isinstance(world, dict):
            self.bathymetry_ref = _bathymetry_ref(world.get("bathymetry"))
            self.transponders = [
                {"id": t.get("id"), "n": t.get("north_m"), "e": t.get("east_m")}
                for t in world.get("transponders") or []
                if isinstance(t, dict)
            ]
        if doc.get("survey"):
            sp = path.parent / str(doc["survey"])
            try:
                self.survey = json.loads(sp.read_text())
            except (OSError, ValueError) as exc:
                raise WorldError(f"{sp}: cannot read the survey ({exc})") from None
        self.publish()

    def observe(self, channel: str, msg: Any) -> None:
        """Pick the layers out of SIM.ANNOTATION and SIM.ENV as they pass."""
        kind = type(msg).__name__
        changed = False
        if kind == "log_annotation_t":
            if msg.kind == 0 and msg.name.endswith("survey.json"):
                try:
                    self.survey, changed = json.loads(msg.text), True
                except ValueError:
                    pass
            elif msg.kind == 1 and msg.vehicle and msg.name.endswith(".sim.yaml"):
                cfg = _sim_config(msg.text)
                if cfg is not None and not self.bathymetry_ref and cfg.env.bathymetry_ref:
                    self.bathymetry_ref, changed = cfg.env.bathymetry_ref, True
                if cfg is not None:
                    self.starts[msg.vehicle] = (cfg.initial.north_m, cfg.initial.east_m)
                    if self.ocean is None and cfg.env.ocean is not None:
                        self.ocean = _ocean(cfg.env, self.base_dir)
                    changed = True
        elif kind == "env_model_t":
            tps = [{"id": t.id, "n": round(t.north_m, 1), "e": round(t.east_m, 1)} for t in msg.transponders]
            if msg.bathymetry_ref != self.bathymetry_ref or tps != self.transponders:
                self.bathymetry_ref, self.transponders, changed = msg.bathymetry_ref, tps, True
            if msg.world and not self.name:
                self.name, changed = msg.world, True
            if self.ocean is None:
                self.ocean = _ocean_of_env_model(msg, self.base_dir)
                changed = changed or self.ocean is not None
        if changed:
            self.publish()

    # ------------------------------------------------------------- layers
    def publish(self) -> None:
        layers: dict[str, Any] = {
            "name": self.name,
            "transponders": self.transponders,
            "bathymetry_ref": self.bathymetry_ref,
        }
        s = self.survey or {}
        layers["survey_area"] = s.get("polygon") or []
        layers["operating_area"] = s.get("operating_area") or []
        lines: dict[str, list] = {}
        areas: dict[str, list] = {}
        for vid, plan in (s.get("vehicles") or {}).items():
            lines[vid] = [[leg["start"], leg["end"]] for leg in plan.get("legs", []) if leg.get("kind") == "line"]
            areas[vid] = plan.get("polygon") or []
        layers["lines"], layers["vehicle_areas"] = lines, areas
        layers["seabed"] = self._seabed(layers)
        layers["water"] = self._water(layers)
        self.model.set_world(layers)

    def _box(self, layers: dict[str, Any], with_starts: bool) -> tuple[float, float, float, float]:
        """The area of interest: the areas, the transponders (and the vehicles' starts), padded."""
        pts = list(layers["operating_area"]) or list(layers["survey_area"])
        pts += [[t["n"], t["e"]] for t in self.transponders if t["n"] is not None]
        if with_starts:
            pts += [list(p) for p in self.starts.values()]
        if not pts:
            return -250.0, 250.0, -250.0, 250.0
        n0, n1 = min(p[0] for p in pts), max(p[0] for p in pts)
        e0, e1 = min(p[1] for p in pts), max(p[1] for p in pts)
        # the vehicles go from their starts: half the span more on every side
        pad = (0.5 if with_starts else 0.15) * max(n1 - n0, e1 - e0, 50.0)
        return n0 - pad, n1 + pad, e0 - pad, e1 + pad

    def _water(self, layers: dict[str, Any]) -> dict[str, Any] | None:
        """The water's temperature at WATER_DEPTH_M at t = 0 on a WATER_GRID square lattice, or None."""
        if self.ocean is None:
            return None
        import numpy as np

        n0, n1, e0, e1 = self._box(layers, with_starts=True)
        k = WATER_GRID
        dn, de = (n1 - n0) / k, (e1 - e0) / k
        nn, ee = np.meshgrid(n0 + (np.arange(k) + 0.5) * dn, e0 + (np.arange(k) + 0.5) * de, indexing="ij")
        try:
            temp = self.ocean.fields(0.0, nn, ee, WATER_DEPTH_M)[0]
        except Exception as exc:  # noqa: BLE001 - a map without the water beats no map
            return {"error": f"ocean: {exc}"}
        rows = np.round(temp, 3).tolist()
        return {"north0": n0, "east0": e0, "dn": dn, "de": de, "depth_m": WATER_DEPTH_M, "t": 0.0, "temp": rows}

    def _seabed(self, layers: dict[str, Any]) -> dict[str, Any] | None:
        """Depths on a GRID x GRID lattice over the area of interest, or None."""
        if not self.bathymetry_ref:
            return None
        try:
            from sim.bathymetry import Bathymetry

            depth = Bathymetry(self.bathymetry_ref, self.base_dir).depth
        except Exception as exc:  # noqa: BLE001 - a map without a seabed beats no map
            return {"error": f"seabed {self.bathymetry_ref!r}: {exc}"}
        n0, n1, e0, e1 = self._box(layers, with_starts=False)
        dn, de = (n1 - n0) / GRID, (e1 - e0) / GRID
        rows = [
            [round(float(depth(n0 + (i + 0.5) * dn, e0 + (j + 0.5) * de)), 2) for j in range(GRID)] for i in range(GRID)
        ]
        return {"north0": n0, "east0": e0, "dn": dn, "de": de, "depth": rows}


def _bathymetry_ref(node: Any) -> str:
    """A scenario names its seabed as a reference string or as {shape: ..., params}."""
    if isinstance(node, dict):
        params = {k: v for k, v in node.items() if k != "shape"}
        if "shape" in node and all(isinstance(v, (int, float)) for v in params.values()):
            return f"{node['shape']}:" + ",".join(f"{k}={params[k]:g}" for k in sorted(params))
        return f"grid:{node['grid']}" if "grid" in node else ""
    return str(node or "")


def _sim_config(text: str) -> Any:
    """A simulator's merged configuration (annotated into the log), or None."""
    try:
        from sim.config import loads

        return loads(text)
    except Exception:  # noqa: BLE001 - an unreadable config just leaves its layers out
        return None


def _ocean(env: Any, base_dir: Path) -> Any:
    """The world's ocean from its environment parameters, or None (no ocean, or a grid file not here)."""
    try:
        from sim.environment import Environment

        return Environment(env, base_dir).ocean
    except Exception:  # noqa: BLE001 - a map without the water beats no map
        return None


def _ocean_of_env_model(msg: Any, base_dir: Path) -> Any:
    try:
        from sim.environment import Environment

        params = Environment.params_from_env_model(msg)
    except Exception:  # noqa: BLE001
        return None
    return _ocean(params, base_dir) if params.ocean is not None else None
