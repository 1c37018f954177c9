"""The one way every configuration file is read and checked (docs/scenarios.md, "Limits").

    read_yaml  bytes -> a composed YAML node tree, with the limits every file gets
    Checker    positions, errors with hints, filling a dataclass field by field
    setting    a dataclass field with its range or choices declared on it

Every error is `file:line:col: key: message`; a tool prints them all and exits 2.
"""

from confcheck.checker import Checker, join
from confcheck.errors import ConfigError, report
from confcheck.names import VEHICLE_ID, vehicle_id_problem
from confcheck.reader import LIMITS, Limits, read_yaml
from confcheck.rules import Rule, rule_of, setting

__all__ = [
    "Checker",
    "ConfigError",
    "LIMITS",
    "Limits",
    "Rule",
    "VEHICLE_ID",
    "join",
    "read_yaml",
    "report",
    "rule_of",
    "setting",
    "vehicle_id_problem",
]
