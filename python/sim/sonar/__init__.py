"""Seabed targets and the sidescan sonar: detections, false alarms, coverage.

The curve, targets and coverage need no LCM types; sim.sonar.sidescan (the
detection model) and sim.sonar.publisher (the HIL hook) do.
"""

from sim.sonar.config import ScoreModel, SonarConfig, TargetArea, TargetsConfig
from sim.sonar.coverage import Coverage, coverage_grid
from sim.sonar.curve import LateralRangeCurve
from sim.sonar.targets import Target, TargetField, TargetFileError

__all__ = [
    "ScoreModel",
    "SonarConfig",
    "TargetArea",
    "TargetsConfig",
    "Coverage",
    "coverage_grid",
    "LateralRangeCurve",
    "Target",
    "TargetField",
    "TargetFileError",
]
