/* libFuzzer target for the binding-file parser (mgr_bindings.c): any bytes
 * as a binding file, bound against a small plan that has inputs and outputs
 * of every variable type, so both the syntax and the binding of fields are
 * exercised. Driven by libFuzzer (clang) or c/chasm/fuzz/fuzz_driver.c. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "chasm/chasm.h"
#include "managers/mgr_bindings.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char plan[] =
    "input nav.depth_m: double m\n"
    "input nav.vehicle: string\n"
    "input gps.valid: bool\n"
    "output setpoint.depth_m: double m\n"
    "output setpoint.vertical_mode: int\n"
    "state s {\n  do set setpoint.depth_m = 1 m\n}\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static chasm_machine *m;
    if (!m) {
        chasm_options o;
        memset(&o, 0, sizeof o);
        m = chasm_load_string("fuzz_plan.chasm", plan, sizeof plan - 1, &o, NULL);
        if (!m)
            __builtin_trap();
    }
    mgr_bindings b;
    mgr_errors errs = {.quiet = 1};
    /* stderr would drown the fuzzer: errors are only collected */
    (void)mgr_bindings_load_text(&b, "fuzz.bind", (const char *)data, size, "AUV1", m, &errs);
    for (size_t i = 0; i < errs.n; i++)
        (void)strlen(errs.lines[i]);
    mgr_errors_free(&errs);
    mgr_bindings_free(&b, NULL);
    return 0;
}
