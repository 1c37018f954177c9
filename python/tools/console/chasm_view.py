"""The state view's half of the console model: each manager's plan structure
(chasm_structure_t on <VEHICLE>.PLAN.<MANAGER>) checked before it is drawn,
and what a status adds to it (the live test values, the variables, the
transition history).

A structure is refused, counted and its reason kept (shown on the page) when
it contradicts itself: a parent, child, next or transition end that is no
state, a cycle of parents, a test range outside its table, or more states or
transitions than a page can draw. A status whose plan_id is not the
structure's is shown without the tree, and counted: the view never draws a
state the manager did not report.
"""

from __future__ import annotations

import math
from typing import Any

MAX_STATES = 5000  # more than this is not drawn: the page must stay responsive
MAX_TRANSITIONS = 20000
HISTORY_KEEP = 50  # transitions kept per manager


class BadStructure(ValueError):
    pass


def _index(i: int, n: int, what: str, allow_none: bool = True) -> int:
    if (allow_none and i == -1) or 0 <= i < n:
        return i
    raise BadStructure(f"{what} is {i}, not a state (0..{n - 1})")


def check_structure(msg: Any) -> dict[str, Any]:
    """The structure as the page draws it; BadStructure says why not."""
    n = msg.n_states
    if msg.truncated:
        raise BadStructure(f"the manager could not send it: {msg.note or 'too big'}")
    if n > MAX_STATES or msg.n_transitions > MAX_TRANSITIONS:
        raise BadStructure(f"{n} states and {msg.n_transitions} transitions: more than the view draws ({MAX_STATES})")
    if n == 0:
        raise BadStructure("no states")
    if len(msg.plan_id) != 16:
        raise BadStructure(f"plan_id '{msg.plan_id[:20]}' is not 16 hex digits")
    parents = [_index(p, n, f"state {i}'s parent") for i, p in enumerate(msg.state_parent)]
    for i in range(n):  # a chain of parents longer than the states is a cycle
        seen, p = 0, parents[i]
        while p != -1:
            seen += 1
            if seen > n or p == i:
                raise BadStructure(f"state '{msg.state_path[i]}' is its own ancestor")
            p = parents[p]
    for i in range(n):
        _index(msg.state_default_child[i], n, f"state {i}'s start child")
        _index(msg.state_next[i], n, f"state {i}'s next")
        c = msg.state_default_child[i]
        if c != -1 and parents[c] != i:
            raise BadStructure(f"the start child of '{msg.state_path[i]}' is not its child")
    _index(msg.initial_state, n, "the initial state")
    trans = []
    for k in range(msg.n_transitions):
        first, count = msg.trans_first_test[k], msg.trans_n_tests[k]
        if first < 0 or count < 0 or first + count > msg.n_trans_tests:
            raise BadStructure(f"transition {k}'s tests {first}+{count} are outside the {msg.n_trans_tests} named")
        trans.append(
            {
                "from": _index(msg.trans_from[k], n, f"transition {k}'s source"),
                "to": _index(msg.trans_to[k], n, f"transition {k}'s target", allow_none=False),
                "history": msg.trans_history[k],
                "cond": msg.trans_condition[k],
                "tests": list(msg.trans_test_name[first : first + count]),
                "loc": msg.trans_loc[k],
            }
        )
    return {
        "id": msg.plan_id,
        "plan": msg.plan,
        "loaded": msg.loaded_utime / 1e6,
        "states": [
            {
                "name": msg.state_name[i],
                "path": msg.state_path[i],
                "parent": parents[i],
                "start": msg.state_default_child[i],
                "next": msg.state_next[i],
                "next_done": bool(msg.state_next_done[i]),
                "loc": msg.state_loc[i],
            }
            for i in range(n)
        ],
        "initial": msg.initial_state,
        "actions": [
            {"state": msg.action_state[a], "text": msg.action_text[a], "when": msg.action_time_model[a]}
            for a in range(msg.n_actions)
            if 0 <= msg.action_state[a] < n
        ],
        "transitions": trans,
        "vars": [
            {
                "name": msg.var_name[i],
                "kind": ("input", "output", "local")[msg.var_kind[i]] if 0 <= msg.var_kind[i] <= 2 else "?",
                "type": msg.var_type[i],
                "unit": msg.var_unit[i],
            }
            for i in range(msg.n_vars)
        ],
        "params": [[msg.param_name[i], msg.param_value[i]] for i in range(msg.n_params)],
    }


def _number(x: float) -> float | None:
    return None if math.isnan(x) or math.isinf(x) else round(x, 4)


def status_view(msg: Any, old: dict[str, Any] | None) -> dict[str, Any]:
    """The state view's fields of one status (added to the console's manager entry)."""
    history = list(old["history"]) if old else []
    t_last = msg.last_transition_utime / 1e6
    if msg.last_to and (not history or history[-1]["t"] != t_last or history[-1]["to"] != msg.last_to):
        history.append({"t": t_last, "from": msg.last_from, "to": msg.last_to, "cond": msg.last_condition})
        history = history[-HISTORY_KEEP:]
    return {
        "plan_id": msg.plan_id,
        "t": msg.utime / 1e6,
        "active": list(msg.active_path),
        "times": [round(x, 1) for x in msg.time_in_state_s],
        "live": [bool(x) for x in msg.live_test_value],
        "live_cut": bool(msg.live_tests_cut),
        "values": [_number(x) for x in msg.var_value],
        "history": history,
    }
