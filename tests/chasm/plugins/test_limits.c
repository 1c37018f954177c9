/* A plugin with a limit its schema cannot state: a list of at most 4 points
 * (like the operating area's vertex limit of outside_area), declared with
 * CHASM_PLUGIN_CHECK so that a longer list is a load error, not a run-time one. */
#include <stdio.h>
#include <string.h>

#include "chasm/chasm_plugin.h"

#define MAX_POINTS 4
enum { POINTS, OUT, NPARAMS };

static const chasm_param_spec route_params[NPARAMS] = {
    [POINTS] = CHASM_PARAM_REQUIRED_STRING("points", "\"x; x; ...\", at most 4"),
    [OUT] = CHASM_WRITE("out", CHASM_INT, "", "test.count", NULL),
};
static int count(const char *s)
{
    int n = *s ? 1 : 0;
    for (; *s; s++) n += *s == ';';
    return n;
}
static chasm_status_code route_step(chasm_ctx *c, void *st)
{
    (void)st;
    chasm_write_int(c, OUT, count(chasm_param_string(c, POINTS)));
    return CHASM_RUNNING;
}
static const chasm_behavior_spec behaviors[] = {
    {.name = "route", .doc = "follow points", CHASM_SCHEMA(route_params), .step = route_step},
};
static const chasm_param_spec many_params[] = {
    [POINTS] = CHASM_PARAM_REQUIRED_STRING("points", "\"x; x; ...\", at most 4"),
};
static int many_eval(chasm_ctx *c) { return count(chasm_param_string(c, 0)) > 2; }
static const chasm_test_spec tests[] = {
    {.name = "many", .doc = "more than 2 points", CHASM_SCHEMA(many_params), .evaluate = many_eval},
};

CHASM_PLUGIN_CHECK(check);
static int check(const char *item, const chasm_ctx *c, int *slot, char *why, size_t whylen)
{
    (void)item; /* both items keep their points in slot 0 */
    int n = count(chasm_param_string(c, POINTS));
    if (n >= 1 && n <= MAX_POINTS) return 0;
    *slot = POINTS;
    snprintf(why, whylen, "%d points, this plugin takes 1 to %d", n, MAX_POINTS);
    return 1;
}

CHASM_PLUGIN_EXPORT("test_limits", "1.0.0", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));
