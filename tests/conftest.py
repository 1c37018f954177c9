"""Shared fixtures: where the build is, its message types, LCM URLs.

The build folder comes from $AUV_BUILD (default build/), so a second build
tree (e.g. `make BUILD=.build-x`) can be tested without touching the first.
The project's Python is installed in .venv (editable); only the generated
message types are taken from the build under test, here and in children.
"""

from __future__ import annotations

import itertools
import os
import sys
from pathlib import Path

import pytest

from auvlcm import programs

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("AUV_BUILD", ROOT / "build"))
if not BUILD.is_absolute():
    BUILD = ROOT / BUILD

if str(BUILD / "gen" / "python") not in sys.path:
    sys.path.insert(0, str(BUILD / "gen" / "python"))


def _own_network_namespace() -> str:
    """Give this xdist worker a network namespace of its own, with loopback
    multicast as tests/isolated_net.sh sets it up: the workers of one run then
    never hear each other's LCM traffic, whatever ports or groups their tests
    use. Only inside the run's private namespace (where this process is root of
    its user namespace); returns why not, or ''."""
    import ctypes
    import subprocess

    if os.environ.get("AUV_IN_ISOLATED_NET") != "1":
        return "not inside tests/isolated_net.sh"
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.unshare(0x40000000) != 0:  # CLONE_NEWNET, for the calling (main) thread, which runs the tests
        return f"unshare(CLONE_NEWNET): {os.strerror(ctypes.get_errno())}"
    for cmd in ("link set lo up", "link set lo multicast on", "route add 224.0.0.0/4 dev lo"):
        run = subprocess.run(["ip", *cmd.split()], capture_output=True, text=True)
        if run.returncode != 0:
            return f"ip {cmd}: {run.stderr.strip()}"
    return ""


def pytest_configure(config):
    worker = os.environ.get("PYTEST_XDIST_WORKER")
    if worker:
        why = _own_network_namespace()
        if why:  # the per-test ports below still keep most tests apart
            print(f"conftest: worker {worker} shares the network of the others: {why}", file=sys.stderr)


# Every test gets its own multicast port, so tests never hear each other even
# when the suite runs on a host network instead of a private namespace.
_ports = itertools.count(7700 + (os.getpid() % 200) * 10)


@pytest.fixture
def build_dir() -> Path:
    return BUILD


@pytest.fixture(params=["normal", "sanitized"])
def variant_dir(request) -> Path:
    """Run a C test once per build variant: build/ and build/san/ (ASan+UBSan)."""
    return BUILD if request.param == "normal" else BUILD / "san"


def c_program(name: str, sanitized: bool = False) -> Path:
    """Path of a built C program or plugin, e.g. c_program('bin/chasm')."""
    path = (BUILD / "san" if sanitized else BUILD) / name
    if not path.exists():
        pytest.fail(f"{path} is not built: run `make build sanitize` first")
    return path


def manager_cmd(
    plan,
    bind,
    url: str,
    *extra,
    sanitized: bool = False,
    vehicle: str = "AUV1",
    name: str = "NAVIGATOR",
    rate: int = 10,
) -> list:
    """A chasm-manager on the simulation clock (SIM.CLOCK), as the tests start one."""
    build = c_program("bin/chasm-manager", sanitized).parents[1]
    return programs.chasm_manager(
        build, plan=plan, bind=bind, vehicle=vehicle, name=name, lcm_url=url, rate_hz=rate, extra=extra
    )


def fresh_url() -> str:
    """A fresh udpm URL on this host only (ttl=0); for module-scoped runs."""
    return f"udpm://239.255.76.67:{next(_ports)}?ttl=0"


@pytest.fixture
def lcm_url() -> str:
    """A fresh udpm URL on this host only (ttl=0)."""
    return fresh_url()


@pytest.fixture
def own_lcm(lcm_url):
    """A FilteredLcm on lcm_url that receives on a socket of its own (auvlcm/own_socket.py)."""
    from auvlcm.chanfilter import FilteredLcm

    lc = FilteredLcm(lcm_url)
    if lc._own is None:
        pytest.skip("no own socket here (libauvlcm_sender.so not built, or AUV_LCM_READER=0)")
    return lc


def child_environment() -> dict[str, str]:
    """Environment for child processes: the build's message types, sanitizer options."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(BUILD / "gen" / "python")
    env.setdefault("ASAN_OPTIONS", "detect_leaks=1:abort_on_error=0:exitcode=86")
    env.setdefault("UBSAN_OPTIONS", "print_stacktrace=1:halt_on_error=1:exitcode=87")
    return env


@pytest.fixture
def child_env() -> dict[str, str]:
    return child_environment()


# ------------------------------------------------------------ parallel runs
# `make test` runs the suite on pytest-xdist workers with `--dist loadgroup`:
# each test file is one unit of work (its module fixtures run once), and files
# that share a session fixture are one unit together (the fixture runs once).
# The units are made by the scheduler below, from the test's file: xdist's own
# loadgroup marks a test by renaming its node id, which pytest 9 no longer
# lets it do, so every file was split across the workers and an expensive
# module fixture (a team flown, a reference run) was made once per worker.
SHARED_SESSION = {
    "nav/test_nav_replay.py": "nav survey",  # nav_fixtures.survey: a recorded survey
    "nav/test_nav_live.py": "nav survey",
}
# The longest units start first, so no worker is left with a long one at the
# end (measured: `make test PYTEST_ARGS=--durations=0`, docs/contributing.md).
LONGEST_FIRST = [
    "hil/test_hil_wire.py",
    "team/test_team_faults.py",
    "test_demo.py",
    "team/test_team_loss.py",
    "team/test_leader_follower.py",
    "multihil/test_nodes.py",
    "hosts/test_agents.py",
    "missions/test_missions.py",
    "tools/test_montecarlo.py",
    "tools/test_launch.py",
    "nav survey",
    "tools/test_launch_backseat.py",
    "team/test_team_crossing.py",
    "drivers/test_driver_fuzz.py",
    "plugins/test_pilot_closed_loop.py",
    "tools/test_recorder_wire.py",
    "multihil/test_multihost.py",
    "test_docs_commands.py",
    "tools/test_report.py",
    "tools/test_report_deterministic.py",
    "tools/test_sampling_team.py",
    "team/test_team_deterministic.py",
]


def work_unit(nodeid: str) -> str:
    """The unit of work a test belongs to: its file (relative to tests/), or the
    group of files that share a session fixture."""
    path = nodeid.split("::", 1)[0].split("@", 1)[0]
    rel = path.removeprefix("tests/")
    return SHARED_SESSION.get(rel, rel)


@pytest.hookimpl(optionalhook=True)  # a run without xdist (-p no:xdist) has no such hook
def pytest_xdist_make_scheduler(config, log):
    """`--dist loadgroup`: one unit per file (work_unit), handed out in the
    collection's order (LONGEST_FIRST), not xdist's biggest-count-first."""
    if config.getoption("dist", "no") != "loadgroup":
        return None
    from xdist.scheduler import LoadScopeScheduling

    class FileUnits(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return work_unit(nodeid)

    config.option.loadscopereorder = False
    return FileUnits(config, log)


def pytest_collection_modifyitems(config, items):
    rank = {name: i for i, name in enumerate(LONGEST_FIRST)}
    # stable: within a rank the collection order stays
    items.sort(key=lambda it: rank.get(work_unit(it.nodeid), len(rank)))
