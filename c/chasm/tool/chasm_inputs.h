/* Scripted or recorded variable values for `chasm run`. */
#ifndef CHASM_INPUTS_H
#define CHASM_INPUTS_H
#include <stdint.h>

#include "chasm/chasm.h"

typedef struct {
    int64_t t_us;
    int var;
    chasm_type type;
    double d;
    int b;
    char *s;
    size_t seq;
} chasm_input_event;

typedef struct {
    chasm_input_event *ev;
    size_t n;
} chasm_inputs;

/* Two formats: lines "TIME VARIABLE = VALUE" (units allowed: "12 s nav.depth = 5 m")
 * or CSV with a header "time,var1,var2" (time in s, values in the variables' units).
 * Errors are printed as file:line:col and make it return -1. */
int chasm_inputs_read(const char *path, const chasm_machine *m, chasm_inputs *out);
void chasm_inputs_free(chasm_inputs *in);
#endif
