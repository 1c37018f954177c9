"""The state view's model (tools/console/chasm_view.py) without a browser: a
plan structure checked before it is drawn, bad ones counted and refused with
their reason, a status of another plan than the structure counted, the
transition history, and the structures streamed to a page once per plan."""

from __future__ import annotations

import json
import math

from auv import chasm_status_t, chasm_structure_t
from tools.console.model import Model


def structure(plan_id: str = "0123456789abcdef", n: int = 3) -> chasm_structure_t:
    """mission { start leg1; leg1 -> leg2 when counted }, leg2 ... (n states in a chain below the root)."""
    s = chasm_structure_t()
    s.utime, s.vehicle, s.manager, s.plan, s.plan_id = 1_000_000, "AUV1", "NAVIGATOR", "p.chasm", plan_id
    s.n_states = n
    s.state_name = ["mission"] + [f"leg{i}" for i in range(1, n)]
    s.state_path = ["mission"] + [f"mission/leg{i}" for i in range(1, n)]
    s.state_parent = [-1] + [0] * (n - 1)
    s.state_default_child = [1] + [-1] * (n - 1)
    s.state_next = [-1] * n
    s.state_next_done = [False] * n
    s.state_loc = [f"p.chasm:{i + 1}:1" for i in range(n)]
    s.initial_state = 0
    s.n_transitions = 2
    s.trans_from, s.trans_to, s.trans_history = [-1, 1], [0, 2], [0, 0]
    s.trans_condition = ["stale", "counted and deep"]
    s.trans_first_test, s.trans_n_tests, s.trans_loc = [0, 1], [1, 2], ["p.chasm:9:1", "p.chasm:4:5"]
    s.n_trans_tests, s.trans_test_name = 3, ["stale", "counted", "deep"]
    s.n_vars, s.var_name, s.var_kind, s.var_type, s.var_unit = 1, ["nav.depth_m"], [0], ["double"], ["m"]
    s.n_params, s.param_name, s.param_value = 1, ["depth"], ["12 m"]
    return s


def status(plan_id: str = "0123456789abcdef", path=("mission", "leg1"), t_s: float = 2.0) -> chasm_status_t:
    m = chasm_status_t()
    m.utime, m.vehicle, m.manager, m.plan, m.run_state = int(t_s * 1e6), "AUV1", "NAVIGATOR", "p.chasm", 1
    m.path_len, m.active_path, m.time_in_state_s = len(path), list(path), [t_s] * len(path)
    m.last_transition_utime, m.last_from, m.last_to, m.last_condition = 100_000, "", "/".join(path), "start"
    m.plan_id = plan_id
    m.n_live_tests, m.live_test_value = 3, [False, True, False]
    m.n_var_values, m.var_value = 1, [math.nan]
    return m


def _no_nan(name: str):
    raise AssertionError(f"{name} in the page's JSON")


def roundtrip(msg):
    return type(msg).decode(msg.encode())


def test_a_good_structure_is_drawn_and_a_status_of_it_carries_the_live_tests():
    m = Model()
    assert m.apply("AUV1.PLAN.NAVIGATOR", roundtrip(structure()))
    assert m.apply("AUV1.CHASM.NAVIGATOR", roundtrip(status()))
    st = m.structures["AUV1/NAVIGATOR"]
    assert [s["path"] for s in st["states"]] == ["mission", "mission/leg1", "mission/leg2"]
    assert st["transitions"][1]["tests"] == ["counted", "deep"]
    view = m.vehicles["AUV1"]["managers"]["NAVIGATOR"]["view"]
    assert view["live"] == [False, True, False] and view["values"] == [None]  # NaN is no JSON: None
    now = json.loads(m.now_json(), parse_constant=_no_nan)  # a NaN would not parse in a browser
    assert now["plans"]["AUV1/NAVIGATOR"] == {"id": "0123456789abcdef", "refused": 0, "reason": "", "mismatched": 0}
    # a page gets each structure once, again only when the plan changes
    sent: dict[str, str] = {}
    assert list(m.structures_since(sent)) == ["AUV1/NAVIGATOR"]
    m.apply("AUV1.PLAN.NAVIGATOR", roundtrip(structure()))  # sent again by the manager
    assert m.structures_since(sent) == {}


def test_bad_structures_are_counted_and_not_drawn_with_the_reason():
    m = Model()
    cases = []
    cyc = structure()
    cyc.state_parent = [2, 0, 1]  # mission's parent is its own grandchild
    cases.append((cyc, "its own ancestor"))
    orphan = structure()
    orphan.state_parent = [-1, 0, 7]
    cases.append((orphan, "not a state"))
    tests = structure()
    tests.trans_n_tests = [1, 5]
    cases.append((tests, "outside the 3 named"))
    big = structure(n=6000)
    cases.append((big, "more than the view draws"))
    cut = structure()
    cut.truncated, cut.note = True, "9000 states encode to 2000000 bytes"
    cases.append((cut, "could not send it: 9000 states"))
    for i, (msg, reason) in enumerate(cases, 1):
        assert m.apply("AUV1.PLAN.NAVIGATOR", roundtrip(msg))
        info = m.plans["AUV1/NAVIGATOR"]
        assert info["refused"] == i and reason in info["reason"], info
    assert "AUV1/NAVIGATOR" not in m.structures
    m.refuse_structure("AUV1.PLAN.NAVIGATOR", "a message that is no chasm_structure_t")  # did not decode
    assert m.plans["AUV1/NAVIGATOR"]["refused"] == len(cases) + 1


def test_a_status_of_another_plan_is_counted_and_history_kept():
    m = Model()
    m.apply("AUV1.PLAN.NAVIGATOR", roundtrip(structure()))
    m.apply("AUV1.CHASM.NAVIGATOR", roundtrip(status(plan_id="fedcba9876543210")))
    assert m.plans["AUV1/NAVIGATOR"]["mismatched"] == 1
    m.apply("AUV1.CHASM.NAVIGATOR", roundtrip(status()))
    moved = status(path=("mission", "leg2"), t_s=3.0)
    moved.last_transition_utime, moved.last_from, moved.last_condition = 2_500_000, "mission/leg1", "counted"
    m.apply("AUV1.CHASM.NAVIGATOR", roundtrip(moved))
    m.apply("AUV1.CHASM.NAVIGATOR", roundtrip(moved))  # the same transition, reported again
    hist = m.vehicles["AUV1"]["managers"]["NAVIGATOR"]["view"]["history"]
    assert [(h["from"], h["to"], h["cond"]) for h in hist] == [
        ("", "mission/leg1", "start"),
        ("mission/leg1", "mission/leg2", "counted"),
    ]
    assert m.plans["AUV1/NAVIGATOR"]["mismatched"] == 1
