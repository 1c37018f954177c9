"""The `sonar:` section of the simulator configuration (checked in sim.config)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from confcheck import setting


@dataclass
class TargetArea:
    """An axis-aligned box: corner (north_m, east_m), extent north and east."""

    north_m: float = 0.0
    east_m: float = 0.0
    length_m: float = setting(500.0, gt=0.0)  # along north
    width_m: float = setting(500.0, gt=0.0)  # along east


@dataclass
class TargetsConfig:
    file: str = ""  # CSV of targets (relative to the config); "" = place by seed
    seed: int = -1  # -1 = environment.seed: every vehicle of a world sees one field
    mines: int = setting(10, ge=0, le=1000)  # placing is quadratic in the count
    clutter: int = setting(30, ge=0, le=1000)
    min_separation_m: float = setting(10.0, ge=0.0)
    mine_length_m: float = setting(1.5, gt=0.0)
    clutter_length_m: float = setting(0.8, gt=0.0)
    area: TargetArea = field(default_factory=TargetArea)


@dataclass
class ScoreModel:
    """The on-board classifier's confusion model: each contact's mine-likeness score
    (sidescan_contact_t.confidence) is drawn from Beta(mine_a, mine_b) for a mine-like
    object and from Beta(clutter_a, clutter_b) for clutter and seabed false alarms. The
    two overlap, so no threshold separates them perfectly; classification is
    "mine_like" when the score >= threshold."""

    mine_a: float = setting(6.0, gt=0.0, le=1000.0)
    mine_b: float = setting(2.0, gt=0.0, le=1000.0)
    clutter_a: float = setting(2.0, gt=0.0, le=1000.0)
    clutter_b: float = setting(5.0, gt=0.0, le=1000.0)
    threshold: float = setting(0.5, ge=0.0, le=1.0)


@dataclass
class SonarConfig:
    enabled: bool = True
    # lateral range curve (docs/simulator.md, "Seabed and sonar")
    range_m: float = setting(50.0, gt=0.0)  # range setting per side [m]
    nadir_gap_per_altitude: float = setting(1.0, ge=0.0)  # blind ground range = this x altitude
    min_grazing_rad: float = setting(math.radians(5.0), gt=0.0, lt=math.pi / 2)  # far limit: altitude / tan(this)
    knee_fraction: float = setting(0.6, ge=0.0, le=1.0)  # fall-off starts at this fraction of the far limit
    pd_max: float = setting(0.9, ge=0.0, le=1.0)  # detection probability on the plateau
    clutter_pd_factor: float = setting(1.0, ge=0.0)  # clutter objects are detected like mines x this
    min_altitude_m: float = setting(1.0, ge=0.0)  # imaging only between these altitudes
    max_altitude_m: float = setting(30.0, ge=0.0)
    max_attitude_rad: float = setting(math.radians(15.0), ge=0.0)  # roll or pitch beyond: no image
    # detections
    update_hz: float = setting(5.0, gt=0.0, unit="Hz")  # how often the beam's position is evaluated
    along_track_sigma_m: float = setting(0.5, ge=0.0)  # contact position error, along track [m]
    range_sigma_m: float = setting(0.3, ge=0.0)  # contact position error, across track [m]
    score: ScoreModel = field(default_factory=ScoreModel)  # mine-likeness score and classification
    false_alarms_per_km2: float = setting(2.0, ge=0.0)  # seabed false alarms per km^2 imaged
    relook_s: float = setting(10.0, ge=0.0)  # one look per target per pass at most
    # the true field, for evaluation
    publish_targets: str = setting(
        "auto", one_of=("auto", "yes", "no")
    )  # SIM.TARGETS: auto (like SIM.CLOCK) | yes | no
    targets_period_s: float = setting(10.0, ge=0.0)  # republish period [sim s]; 0 = at start only
    targets: TargetsConfig = field(default_factory=TargetsConfig)
    # the contacts at the wire (sim.devices.lcmframe, protocol lcmframe; docs/simulator.md)
    wire: Any = None
