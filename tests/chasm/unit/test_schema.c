/* Plugin schemas (chasm_plugin.h, ABI 3): chasm_param_given for an optional
 * parameter without a default, and the loader's refusal of a table with a
 * hole and of a plugin built for ABI 2. Plugins: tests/chasm/plugins. */
#include <stdio.h>
#include <string.h>

#include "../../harness/plan_test.h"

/* test_given's probe writes given-ness of its slots; has_opt tests it. */
static const char *given_plan(const char *args)
{
    static char plan[1024];
    snprintf(plan, sizeof plan,
             "use test_given\ninput x : double m\n"
             "output test.opt_given : bool\noutput test.def_given : bool\noutput test.in_given : bool\n"
             "output test.opt_value : double m\n"
             "state a {\n do probe(%s)\n test t : has_opt(%s)\n when t -> b\n}\nstate b {\n}\n",
             args, strstr(args, "opt =") ? "opt = 1 m" : "");
    return plan;
}

static void run_probe(const char *args, int opt, int def, int in, double value)
{
    chasm_machine *m = pt_load(given_plan(args));
    if (!m) return;
    pt_start(m, 0);
    pt_run_until(m, 0.1, 0.1);
    CHECK(pt_get(m, "test.opt_given") == opt);
    CHECK(pt_get(m, "test.def_given") == def);
    CHECK(pt_get(m, "test.in_given") == in);
    CHECK(pt_get(m, "test.opt_value") == value);
    CHECK_STR(pt_leaf(m), opt ? "b" : "a"); /* the test handler sees it too */
    chasm_free(m);
}

static void given_vs_not_given(void)
{
    run_probe("", 0, 0, 0, 0.0);                    /* absent: reads 0, not given */
    run_probe("opt = 0 m", 1, 0, 0, 0.0);           /* given as 0: told apart from absent */
    run_probe("opt = 7 m, def = 5 m, in = x", 1, 1, 1, 7.0); /* a default's value, given */
}

/* The plugin's load check sees given-ness too: 13 m is refused only when given. */
static void given_in_the_load_check(void)
{
    CHECK_HAS(pt_first_error(given_plan("opt = 13 m")), "parameter 'opt' of 'probe': 13 m is unlucky");
    CHECK_STR(pt_first_error(given_plan("def = 13 m")), "");
}

static void table_with_hole_refused(void)
{
    CHECK_HAS(pt_first_error("use test_hole\nstate a {\n}\n"),
              "plugin 'test_hole': behavior 'holey': parameter slot 1 of 3 is empty (a hole in its table");
}

static void abi2_plugin_refused(void)
{
    const char *e = pt_first_error("use test_basic_abi2\nstate a {\n}\n");
    CHECK_HAS(e, "chasm_test_basic_abi2.so' was built for plugin ABI 2, this CHASM uses ABI 3");
}

const unit_test schema_tests[] = {
    {"given_vs_not_given", given_vs_not_given},
    {"given_in_the_load_check", given_in_the_load_check},
    {"table_with_hole_refused", table_with_hole_refused},
    {"abi2_plugin_refused", abi2_plugin_refused},
    {NULL, NULL},
};
