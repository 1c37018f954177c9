"""The message layout keeps its own rules: distinct fingerprints, time on
every message, vehicle ids on vehicle channels, units on every quantity, and
docs/channels.md in step with lcmtypes/."""

from __future__ import annotations

import re

from conftest import ROOT

from auvlcm.types import all_types, fingerprint

CHANNELS_DOC = (ROOT / "docs" / "channels.md").read_text()
ROW_RE = re.compile(r"^\| `([^`]+)` \| `(\w+)` \|", re.M)
UNIT_SUFFIX = re.compile(r"_(m|s|us|ms|rad|mps|radps|deg|pa|c|hz|n|nm|rpm|db|m2|rad2|m2ps2|ppm|per_m|mps2)$")


def nested_types() -> set[str]:
    """Types that appear as a field type of another type."""
    return {tn.rsplit(".", 1)[-1] for cls in all_types() for tn in cls.__typenames__ if "." in tn}


def test_fingerprints_are_unique():
    prints = [fingerprint(c) for c in all_types()]
    assert len(set(prints)) == len(prints)


def test_every_message_starts_with_utime():
    for cls in all_types():
        if cls.__name__ not in nested_types():
            assert cls.__slots__[0] == "utime", cls.__name__
            assert cls.__typenames__[0] == "int64_t", cls.__name__


def test_channels_doc_names_every_message_type_and_only_real_ones():
    documented = {t for _, t in ROW_RE.findall(CHANNELS_DOC)}
    messages = {c.__name__ for c in all_types()} - nested_types()
    assert documented == messages
    for nested in nested_types():
        assert f"`{nested}`" in CHANNELS_DOC, f"{nested} not listed as nested"


def test_vehicle_channels_carry_the_vehicle_id():
    by_name = {c.__name__: c for c in all_types()}
    for channel, type_name in ROW_RE.findall(CHANNELS_DOC):
        if channel.startswith("<VEHICLE>."):
            assert "vehicle" in by_name[type_name].__slots__, f"{channel}: {type_name}"


def test_every_quantity_has_a_unit():
    """A float field needs a unit suffix or a comment with [unit] (or [-])."""
    missing = []
    for path in sorted((ROOT / "lcmtypes").glob("*.lcm")):
        for n, line in enumerate(path.read_text().splitlines(), 1):
            m = re.match(r"\s*(double|float)\s+(\w+)", line)
            if m and not UNIT_SUFFIX.search(m.group(2)) and not re.search(r"//.*\[[^\]]+\]", line):
                missing.append(f"{path.name}:{n}: {m.group(2)}")
    assert not missing, "fields without a unit:\n" + "\n".join(missing)


def test_every_world_message_of_a_server_carries_its_term():
    """Receivers refuse clocks and world messages of an election term that is over
    (a paused server resuming, issue 12): each needs the term to tell."""
    from auv import env_election_t, env_heartbeat_t, env_model_t, env_sample_t, sim_clock_t

    for cls in (sim_clock_t, env_model_t, env_sample_t, env_heartbeat_t, env_election_t):
        assert "term" in cls.__slots__, cls.__name__
        assert cls.__typenames__[cls.__slots__.index("term")] == "int32_t", cls.__name__
