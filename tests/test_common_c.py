"""C helpers that managers build on: field paths (blackboard bindings) and
SHA-256 (plugin upload checks), checked against Python's own answers."""

from __future__ import annotations

import hashlib
import random
import subprocess

import pytest
from conftest import c_program
from lcm_samples import random_message

from auv import dvl_t, ground_truth_t, nav_solution_t, setpoint_t


def probe(*args, sanitized=False):
    return subprocess.run(
        [c_program("bin/auv-lcm-probe", sanitized), *map(str, args)], capture_output=True, text=True, timeout=30
    )


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_field_paths_read_the_values_python_wrote(tmp_path, sanitized):
    rng = random.Random(11)
    cases = [
        (nav_solution_t, "depth_m", lambda m: m.depth_m),
        (nav_solution_t, "position_cov_m2[1][2]", lambda m: m.position_cov_m2[1][2]),
        (nav_solution_t, "status", lambda m: m.status),
        (ground_truth_t, "eta[5]", lambda m: m.eta[5]),
        (dvl_t, "beam_range_m[3]", lambda m: m.beam_range_m[3]),
        (dvl_t, "mode", lambda m: m.mode),
        (setpoint_t, "vertical_mode", lambda m: m.vertical_mode),
    ]
    for cls, path, get in cases:
        msg = random_message(cls, rng)
        f = tmp_path / f"{cls.__name__}.bin"
        f.write_bytes(msg.encode())
        run = probe("field", cls.__name__, path, f, sanitized=sanitized)
        assert run.returncode == 0, run.stderr
        assert float(run.stdout) == pytest.approx(float(get(msg)), rel=1e-15), path
    msg = random_message(nav_solution_t, rng)
    f = tmp_path / "nav.bin"
    f.write_bytes(msg.encode())
    assert probe("field", "nav_solution_t", "vehicle", f).stdout.rstrip("\n") == msg.vehicle


@pytest.mark.parametrize(
    "path,error",
    [
        ("depht_m", "nav_solution_t has no field 'depht_m' (did you mean 'depth_m'?)"),
        ("zzzzzzzzzz", "nav_solution_t has no field 'zzzzzzzzzz'"),
        ("position_cov_m2[3][0]", "'position_cov_m2[3][0]': index 3 out of range [0, 3)"),
        ("position_cov_m2[1]", "'position_cov_m2[1]': position_cov_m2 is an array of 2 dimension(s): give every index"),
        ("depth_m[0]", "'depth_m[0]': depth_m has 0 dimension(s)"),
        ("depth_m[x]", "'depth_m[x]': bad index"),
    ],
)
def test_field_path_errors_say_what_is_wrong(tmp_path, path, error):
    f = tmp_path / "nav.bin"
    f.write_bytes(nav_solution_t().encode())
    run = probe("field", "nav_solution_t", path, f)
    assert run.returncode == 1
    assert run.stderr.strip() == error


def test_variable_arrays_cannot_be_bound(tmp_path):
    from auv import lbl_ranges_t

    f = tmp_path / "lbl.bin"
    f.write_bytes(lbl_ranges_t().encode())
    run = probe("field", "lbl_ranges_t", "two_way_travel_s[0]", f)
    assert run.returncode == 1 and "variable length" in run.stderr


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_sha256_matches_hashlib(tmp_path, sanitized):
    rng = random.Random(4)
    sizes = [0, 1, 55, 56, 63, 64, 65, 119, 120, 1000, 1 << 20]
    for size in sizes:
        data = bytes(rng.getrandbits(8) for _ in range(size)) if size < 5000 else rng.randbytes(size)
        f = tmp_path / f"blob{size}"
        f.write_bytes(data)
        run = probe("sha256", f, sanitized=sanitized)
        assert run.returncode == 0
        assert run.stdout.strip() == hashlib.sha256(data).hexdigest(), f"{size} bytes"
