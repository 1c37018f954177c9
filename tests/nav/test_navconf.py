"""auv-navconf: the nav config a simulated vehicle's filter gets."""

from __future__ import annotations

import subprocess
import sys

import pytest
from conftest import ROOT

NAVCONF = ("-m", "tools.nav.navconf")


def navconf(*args, env=None):
    return subprocess.run(
        [sys.executable, *NAVCONF, *map(str, args)], capture_output=True, text=True, timeout=60, env=env
    )


@pytest.mark.parametrize("name", sorted(p.stem for p in (ROOT / "missions" / "nav").glob("*.nav")))
def test_shipped_nav_configs_are_what_the_generator_writes(name, child_env):
    p = navconf(ROOT / "missions" / "sim" / f"{name}.yaml", env=child_env)
    assert p.returncode == 0, p.stderr
    assert p.stdout == (ROOT / "missions" / "nav" / f"{name}.nav").read_text(), (
        f"regenerate: python/tools/nav/navconf.py missions/sim/{name}.yaml -o missions/nav/{name}.nav"
    )


def test_specifications_not_truths_and_a_submerged_launch(tmp_path, child_env):
    sim = tmp_path / "w.yaml"
    sim.write_text("""vehicle: {id: AUV2}
initial: {north_m: 12.5, east_m: -3, depth_m: 10}
environment:
  sound_speed_mps: 1480
  sound_speed_gradient_per_m: 0.02
  transponders:
    - {id: 7, north_m: 100, east_m: 50, depth_m: 30, turnaround_s: 0.04}
sensors:
  ahrs: {noise: 0.01, bias: -0.03}
  depth: {}
  dvl: {noise: 0.02}
  gps: {noise: 3}
  lbl: {noise: 2}
""")
    p = navconf(sim, env=child_env)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert "compass_noise_rad 0.01" in lines
    assert "compass_bias_sigma_rad 0.03" in lines  # the bias's size, as a 1-sigma prior
    assert "dvl_noise_mps 0.02" in lines and "gps_noise_m 3" in lines and "lbl_range_noise_m 2" in lines
    assert "sound_speed_mps 1480" in lines and "sound_speed_gradient_per_m 0.02" in lines
    assert "transponder 7 100 50 30 0.04" in lines
    assert "initial_north_m 12.5" in lines and "initial_east_m -3" in lines  # no GPS fix at 10 m


def test_a_bad_simulator_config_exits_2_with_its_errors(tmp_path, child_env):
    sim = tmp_path / "bad.yaml"
    sim.write_text("sensors:\n  ahrs: {nosie: 0.1}\n")
    p = navconf(sim, env=child_env)
    assert p.returncode == 2
    assert f"{sim}:2:" in p.stderr and "nosie" in p.stderr
