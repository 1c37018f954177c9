"""`auv-lcmlog mcap`: a log of every message type, read back from the MCAP: the
same channels with the same counts, every message valid against its schema
(generated from lcmtypes/), values that survive, derived map topics, and
events that do not decode counted and left out."""

from __future__ import annotations

import json
import math
import random
import subprocess
import sys
from collections import Counter

import jsonschema
import lcm
from lcm_samples import random_message
from mcap.reader import make_reader

from auv import env_model_t, log_annotation_t, nav_solution_t
from auvlcm.json_schema import all_schemas, to_json
from auvlcm.types import all_types

LCMLOG = [sys.executable, "-m", "tools.logs.lcmlog"]
SURVEY = {
    "polygon": [[0, 0], [100, 0], [100, 80], [0, 80]],
    "operating_area": [[-50, -50], [150, -50], [150, 130]],
    "vehicles": {
        "AUV1": {
            "legs": [
                {"kind": "line", "start": [0, 10], "end": [100, 10]},
                {"kind": "turn", "start": [100, 10], "end": [100, 40]},
            ]
        }
    },
}


def write_log(path) -> Counter:
    """Every type on its own channel, a vehicle's NAV with a NaN, the world, and two bad events."""
    rng = random.Random(17)
    log = lcm.EventLog(str(path), "w", overwrite=True)
    expected: Counter = Counter()
    t = 1_000_000

    def put(channel: str, data: bytes, counted: bool = True) -> None:
        nonlocal t
        t += 1000
        log.write_event(t, channel, data)
        if counted:
            expected[channel] += 1

    env = env_model_t()
    env.origin_latitude_deg, env.origin_longitude_deg, env.bathymetry_ref = 41.5, -70.7, "flat:depth=20"
    put("SIM.ENV", env.encode())
    note = log_annotation_t()
    note.kind, note.name, note.text = 0, "survey.json", json.dumps(SURVEY)
    put("SIM.ANNOTATION", note.encode())
    for cls in all_types():
        for _ in range(3):
            put(f"T.{cls.__name__}", random_message(cls, rng).encode())
    for i in range(5):
        nav = nav_solution_t()
        nav.utime, nav.vehicle, nav.north_m, nav.latitude_deg, nav.longitude_deg = i * 100_000, "AUV1", i, 41.5, -70.7
        nav.altitude_m = math.nan if i == 2 else 3.0
        put("AUV1.NAV", nav.encode())
    put("AUV1.NAV", nav.encode()[:-5], counted=False)  # truncated
    put("AUV1.JUNK", b"\x01" * 40, counted=False)  # unknown fingerprint
    put("LCM_SELF_TEST", b"self test", counted=False)  # liblcm's own
    log.close()
    return expected


def test_every_channel_and_message_comes_back_valid_against_its_schema(tmp_path, child_env):
    expected = write_log(tmp_path / "t.lcmlog")
    out = tmp_path / "t.mcap"
    run = subprocess.run(
        LCMLOG + ["mcap", str(tmp_path / "t.lcmlog"), str(out)],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 1, run.stdout + run.stderr  # the two bad events are reported
    assert "2 undecodable event(s)" in run.stderr and "Traceback" not in run.stderr

    counts: Counter = Counter()
    validators: dict[int, jsonschema.Draft202012Validator] = {}
    messages: dict[str, list] = {}
    with open(out, "rb") as f:
        for schema, channel, message in make_reader(f).iter_messages():
            assert channel.message_encoding == "json" and schema.encoding == "jsonschema"
            if schema.id not in validators:
                doc = json.loads(schema.data)
                jsonschema.Draft202012Validator.check_schema(doc)
                validators[schema.id] = jsonschema.Draft202012Validator(doc)
            obj = json.loads(message.data)
            validators[schema.id].validate(obj)
            counts[channel.topic] += 1
            messages.setdefault(channel.topic, []).append((schema.name, obj))
    lcm_topics = {k: v for k, v in counts.items() if not k.startswith("derived/")}
    assert lcm_topics == dict(expected)
    assert messages["T.chasm_status_t"][0][0] == "auv.chasm_status_t"

    # values survive: NaN as null, the rest exact
    navs = [obj for _, obj in messages["AUV1.NAV"]]
    assert [n["north_m"] for n in navs] == [0, 1, 2, 3, 4] and navs[2]["altitude_m"] is None
    # derived: positions for the map panel and the survey as GeoJSON
    assert counts["derived/AUV1/nav_position"] == 5
    fix = messages["derived/AUV1/nav_position"][0]
    assert fix[0] == "foxglove.LocationFix" and fix[1]["latitude"] == 41.5
    geo = json.loads(messages["derived/survey_geojson"][0][1]["geojson"])
    names = [f["properties"]["name"] for f in geo["features"]]
    assert names[:3] == ["survey area", "operating area", "AUV1 lines"]
    ring = geo["features"][0]["geometry"]["coordinates"][0]
    assert ring[0] == ring[-1] and ring[0] == [-70.7, 41.5]
    assert len(geo["features"][2]["geometry"]["coordinates"]) == 1  # lines only, not turns


def test_schemas_reject_what_the_type_cannot_hold():
    schemas = all_schemas()
    assert set(schemas) == {f"auv.{c.__name__}" for c in all_types()}
    v = jsonschema.Draft202012Validator(schemas["auv.nav_solution_t"])
    good = to_json(nav_solution_t())
    assert v.is_valid(good)
    for bad in (
        {**good, "status": 2**31},
        {**good, "vehicle": 3},
        {**good, "extra": 1},
        {**good, "position_cov_m2": [[0, 0, 0]] * 2},
        {k: x for k, x in good.items() if k != "utime"},
    ):
        assert not v.is_valid(bad), bad


def test_a_missing_log_is_a_usage_error(tmp_path, child_env):
    run = subprocess.run(
        LCMLOG + ["mcap", str(tmp_path / "none.lcmlog"), str(tmp_path / "x.mcap")],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.returncode == 2 and "no such log" in run.stderr
