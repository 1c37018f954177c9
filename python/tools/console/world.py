"""The map's fixed layers: survey area and lines, operating area, LBL net, seabed.

They come from wherever they are known, the latest source winning: a scenario
file given on the command line, the log's own annotations (the planner's
survey.json, each simulator's merged configuration) and SIM.ENV (the seabed
reference and the transponders the environment server serves).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import yaml

from tools.console.model import Model

GRID = 40  # seabed cells per side sent to the page


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
            elif msg.kind == 1 and msg.vehicle and msg.name.endswith(".sim.yaml") and not self.bathymetry_ref:
                ref = _bathymetry_of_sim_yaml(msg.text)
                if ref:
                    self.bathymetry_ref, changed = ref, True
        elif kind == "env_model_t":
            tps = [{"id": t.id, "n": round(t.north_m, 1), "e": round(t.east_m, 1)} for t in msg.transponders]
            if msg.bathymetry_ref != self.bathymetry_ref or tps != self.transponders:
                self.bathymetry_ref, self.transponders, changed = msg.bathymetry_ref, tps, True
            if msg.world and not self.name:
                self.name, changed = msg.world, True
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
        self.model.set_world(layers)

    def _seabed(self, layers: dict[str, Any]) -> dict[str, Any] | None:
        """Depths on a GRID x GRID lattice over the area of interest, or None."""
        if not self.bathymetry_ref:
            return None
        try:
            from sim.bathymetry import Bathymetry

            depth = Bathymetry(self.bathymetry_ref, self.base_dir).depth
        except Exception as exc:  # noqa: BLE001 - a map without a seabed beats no map
            return {"error": f"seabed {self.bathymetry_ref!r}: {exc}"}
        pts = list(layers["operating_area"]) or list(layers["survey_area"])
        pts += [[t["n"], t["e"]] for t in self.transponders if t["n"] is not None]
        if pts:
            n0, n1 = min(p[0] for p in pts), max(p[0] for p in pts)
            e0, e1 = min(p[1] for p in pts), max(p[1] for p in pts)
            pad = 0.15 * max(n1 - n0, e1 - e0, 50.0)
            n0, n1, e0, e1 = n0 - pad, n1 + pad, e0 - pad, e1 + pad
        else:
            n0, n1, e0, e1 = -250.0, 250.0, -250.0, 250.0
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


def _bathymetry_of_sim_yaml(text: str) -> str:
    try:
        from sim.config import loads

        return loads(text).env.bathymetry_ref or ""
    except Exception:  # noqa: BLE001 - an unreadable config just leaves the seabed out
        return ""
