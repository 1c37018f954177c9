"""sim.wire's precompiled encoders are byte-identical to lcm-gen's encode()."""

from __future__ import annotations

import random

import pytest

from auv import (
    actuator_state_t,
    ahrs_t,
    altimeter_t,
    depth_t,
    dvl_t,
    gps_fix_t,
    ground_truth_t,
    lbl_ranges_t,
    nav_solution_t,
    process_health_t,
    sim_clock_t,
    target_field_t,
)
from sim.wire import Encoder, fixed_layout

# every fixed-layout type the simulator publishes, with its fixed strings
SENT = [
    (ahrs_t, {"vehicle": "AUV1"}),
    (depth_t, {"vehicle": "AUV1"}),
    (dvl_t, {"vehicle": "AUV1"}),
    (altimeter_t, {"vehicle": "AUV1"}),
    (gps_fix_t, {"vehicle": "AUV1"}),
    (nav_solution_t, {"vehicle": "AUV1"}),
    (ground_truth_t, {"vehicle": "AUV1"}),
    (actuator_state_t, {"vehicle": "AUV1"}),
    (process_health_t, {"vehicle": "AUV1", "process": "sim"}),
    (sim_clock_t, {"server_id": "AUV1-sim"}),
]
RANGES = {"int8_t": 7, "int16_t": 15, "int32_t": 31, "int64_t": 63}


def random_value(rng: random.Random, typename: str):
    if typename in RANGES:
        bits = RANGES[typename]
        return rng.randint(-(2**bits), 2**bits - 1)
    if typename == "boolean":
        return rng.random() < 0.5
    if typename == "float":
        return rng.uniform(-1e3, 1e3)
    return rng.choice([rng.uniform(-1e6, 1e6), rng.gauss(0.0, 1e-3), 0.0, -0.0, 1e300])


def random_message(cls, strings: dict, rng: random.Random):
    msg = cls()
    for name, tn, dims in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__):
        if tn == "string":
            setattr(msg, name, strings[name])
        elif dims is None:
            setattr(msg, name, random_value(rng, tn))
        elif len(dims) == 1:
            setattr(msg, name, [random_value(rng, tn) for _ in range(dims[0])])
        else:
            setattr(msg, name, [[random_value(rng, tn) for _ in range(dims[1])] for _ in range(dims[0])])
    return msg


def flat_values(msg) -> list:
    out = []
    cls = type(msg)
    for name, tn, dims in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__):
        if tn == "string":
            continue
        v = getattr(msg, name)
        if dims is None:
            out.append(v)
        elif len(dims) == 1:
            out.extend(v)
        else:
            for row in v:
                out.extend(row)
    return out


@pytest.mark.parametrize("cls,strings", SENT, ids=[c.__name__ for c, _ in SENT])
def test_encoder_is_byte_identical_to_lcm_gen(cls, strings):
    rng = random.Random(cls.__name__)
    enc = Encoder(cls, **strings)
    for _ in range(300):
        msg = random_message(cls, strings, rng)
        expected = msg.encode()
        assert enc.encode(msg) == expected
        assert enc.pack(*flat_values(msg)) == expected
        assert enc.size == len(expected)
        assert cls.decode(enc.encode(msg)).encode() == expected


def test_out_of_range_values_raise_like_lcm_gen():
    enc = Encoder(ahrs_t, vehicle="AUV1")
    msg = ahrs_t()
    msg.vehicle, msg.utime = "AUV1", 2**63
    with pytest.raises(Exception):
        msg.encode()
    with pytest.raises(Exception):
        enc.encode(msg)


def test_variable_layouts_and_missing_strings_are_refused():
    assert not fixed_layout(lbl_ranges_t) and not fixed_layout(target_field_t)
    with pytest.raises(ValueError, match="variable"):
        Encoder(lbl_ranges_t, vehicle="AUV1")
    with pytest.raises(ValueError, match="fixed value"):
        Encoder(process_health_t, vehicle="AUV1")
    with pytest.raises(ValueError, match="no field"):
        Encoder(ahrs_t, vehicle="AUV1", colour="red")
