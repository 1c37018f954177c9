/* libFuzzer target for the Loader: any bytes as a plan. A plan that loads is
 * also started and stepped, so the runtime is fuzzed on every valid plan. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "chasm/chasm.h"
#include "chasm/chasm_structure.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The same bytes as a -D value: overrides are values, never plan text. */
static void fuzz_override(const uint8_t *data, size_t size)
{
    static const char plan[] = "param depth = 1 m\nparam name = \"x\"\nstate a {\n}\n";
    char value[256];
    size_t n = size < sizeof value - 1 ? size : sizeof value - 1;
    memcpy(value, data, n);
    value[n] = 0;
    const char *names[] = {"depth", "name"}, *values[] = {value, value};
    chasm_options o;
    memset(&o, 0, sizeof o);
    o.param_names = names;
    o.param_values = values;
    o.n_params = 2;
    chasm_errors *e = NULL;
    chasm_machine *m = chasm_load_string("fuzz_d.chasm", plan, sizeof plan - 1, &o, &e);
    chasm_errors_free(e);
    if (m && chasm_state_count(m) != 1) __builtin_trap(); /* an override injected a state */
    chasm_free(m);
}

static void no_finding(void *user, chasm_where w, const char *kind, const char *message)
{
    (void)user, (void)kind, (void)message;
    if (!w.file) __builtin_trap();
}

/* What views read of a loaded plan (chasm_structure.h): every state, action,
 * transition and parameter, and the deeper checks. */
static void describe(const chasm_machine *m)
{
    chasm_state_info s;
    chasm_action_info a;
    chasm_trans_info t;
    char buf[64];
    for (int i = 0; chasm_state_info_get(m, i, &s) == 0; i++) {
        if (s.parent >= i || s.default_child >= (int)chasm_state_count(m)) __builtin_trap(); /* parents first */
        for (int k = 0; k < s.n_actions; k++) chasm_action_info_get(m, i, k, &a);
        for (int k = 0; k < s.n_transitions; k++)
            if (chasm_trans_info_get(m, i, k, &t) || t.from != i) __builtin_trap();
    }
    for (int k = 0; k < chasm_abort_count(m); k++) chasm_trans_info_get(m, -1, k, &t);
    for (size_t i = 0; i < chasm_param_count(m); i++) (void)chasm_param_get(m, i, buf, sizeof buf);
    chasm_lint(m, no_finding, NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_override(data, size);
    chasm_errors *e = NULL;
    chasm_machine *m = chasm_load_string("fuzz.chasm", (const char *)data, size, NULL, &e);
    for (size_t i = 0; i < chasm_errors_count(e); i++) (void)chasm_errors_get(e, i);
    chasm_errors_free(e);
    if (!m) return 0;
    describe(m);
    chasm_start(m, 0);
    for (int64_t t = 1; t <= 50; t++) {
        /* feed every variable something, so tests flip */
        for (size_t v = 0; v < chasm_var_count(m); v++) {
            if (chasm_var_kind_of(m, (int)v) != CHASM_VAR_INPUT) continue;
            chasm_var_set_double(m, (int)v, (double)(t % 7), t * 100000);
            chasm_var_set_int(m, (int)v, t % 5, t * 100000);
            chasm_var_set_bool(m, (int)v, t % 3 == 0, t * 100000);
        }
        if (chasm_step(m, t * 100000) != CHASM_RUN_RUNNING) break;
        chasm_status st;
        chasm_status_get(m, t * 100000, &st);
        bool live[8];
        (void)chasm_live_tests(m, live, 8);
    }
    chasm_free(m);
    return 0;
}
