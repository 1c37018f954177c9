/* chasm_structure.h: a plan described for views (states, transitions with
 * the tests they name, parameters) and the live test values in the order
 * the managers publish them (aborts, then the active path root first). */
#include <math.h>
#include <string.h>

#include "../../harness/plan_test.h"
#include "chasm/chasm_structure.h"

#define PLAN                                                                                                        \
    "param depth = 12 m\n"                                                                                          \
    "input x : double m\noutput y : double m\n"                                                                     \
    "test stale : age x > 5 s\nabort when stale -> safe\n"                                                          \
    "state a {\n  test hi : x > 1 m\n  test lo : x < 0 m\n  when hi and lo -> safe\n"                              \
    "  state b {\n    do set y = $depth on entry\n    when hi -> c\n  }\n  state c {\n  }\n}\n"                    \
    "state safe {\n}\n"

static void structure_of_a_plan(void)
{
    chasm_machine *m = pt_load(PLAN);
    if (!m) return;
    CHECK(chasm_state_count(m) == 4);
    chasm_state_info s;
    CHECK(chasm_state_info_get(m, 1, &s) == 0);
    CHECK_STR(s.path, "a/b");
    CHECK(s.parent == 0 && s.n_actions == 1 && s.n_transitions == 1 && s.where.line == 10);
    CHECK(chasm_state_info_get(m, 4, &s) == -1);
    chasm_state_info a;
    chasm_state_info_get(m, 0, &a);
    CHECK(a.default_child == 1 && a.parent == -1);
    chasm_action_info act;
    CHECK(chasm_action_info_get(m, 1, 0, &act) == 0);
    CHECK_STR(act.time_model, "entry");
    CHECK_HAS(act.text, "set y");
    chasm_trans_info t;
    CHECK(chasm_abort_count(m) == 1 && chasm_trans_info_get(m, -1, 0, &t) == 0);
    CHECK(t.from == -1 && t.to == 3 && t.n_tests == 1);
    CHECK_STR(t.test_name[0], "stale");
    CHECK(chasm_trans_info_get(m, 0, 0, &t) == 0 && t.n_tests == 2);
    CHECK_STR(t.condition, "hi and lo");
    char buf[64];
    CHECK(chasm_param_count(m) == 1);
    CHECK_STR(chasm_param_get(m, 0, buf, sizeof buf), "depth");
    CHECK_STR(buf, "12 m");
    chasm_free(m);
}

static void live_tests_follow_the_active_path(void)
{
    chasm_machine *m = pt_load(PLAN);
    if (!m) return;
    chasm_start(m, 0);
    pt_set(m, "x", 2, 0);
    chasm_step(m, 100000); /* a/b -> a/c on hi */
    CHECK_STR(pt_leaf(m), "a/c");
    bool v[8];
    /* stale; a: hi, lo; c has no transitions */
    CHECK(chasm_live_tests(m, v, 8) == 3);
    CHECK(!v[0] && v[1] && !v[2]);
    CHECK(chasm_live_tests(m, v, 1) == 3); /* a short buffer: the count, nothing past it */
    CHECK(chasm_var_number(m, chasm_var_find(m, "x")) == 2.0);
    CHECK(!isnan(chasm_var_number(m, chasm_var_find(m, "y"))));
    CHECK(isnan(chasm_var_number(m, 99)));
    chasm_free(m);
}

static int n_found;
static char kinds[256];
static void on_finding(void *user, chasm_where w, const char *kind, const char *message)
{
    (void)user, (void)w, (void)message;
    n_found++;
    strncat(kinds, kind, sizeof kinds - strlen(kinds) - 2);
    strcat(kinds, " ");
}

/* `hi and lo` asks x for > 1 m and < 0 m; `safe` has no way out (a/c has: a's transition, though it never fires). */
static void lint_findings(void)
{
    chasm_machine *m = pt_load(PLAN);
    if (!m) return;
    n_found = 0;
    kinds[0] = 0;
    CHECK(chasm_lint(m, on_finding, NULL) == 2 && n_found == 2);
    CHECK_STR(kinds, "never-fires no-way-out ");
    chasm_free(m);
}

const unit_test structure_tests[] = {
    {"structure_of_a_plan", structure_of_a_plan},
    {"live_tests_follow_the_active_path", live_tests_follow_the_active_path},
    {"lint_findings", lint_findings},
    {NULL, NULL},
};
