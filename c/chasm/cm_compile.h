/* Shared by the Loader's compile passes (cm_compile*.c, cm_plugins.c). */
#ifndef CM_COMPILE_H
#define CM_COMPILE_H
#include "chasm/cm_machine.h"

typedef struct {
    cm_loc loc;
    const char *desc;           /* "action 'set' in state 'descend'" */
    cm_state *state;            /* NULL: the vehicle (an input) */
} cm_writer;

typedef struct {
    chasm_machine *m;
    cm_arena *a;
    cm_diag *d;
    cm_aplan *plan;
    cm_map path_map;            /* full path -> state */
    cm_map name_map;            /* bare name -> state, or &cc->ambiguous */
    cm_map test_map;            /* "path:name" or ":name" -> test */
    cm_map plugin_map;          /* plugin name -> cm_plugin */
    int ambiguous;
    cm_writer **writers;        /* per variable: dynamic array */
    int *n_writers, *cap_writers;
} cm_cc;

/* Converts a written value to type/unit (unit NULL: plain). 0 on success. */
int cm_value(cm_cc *cc, const cm_aval *v, chasm_type type, const cm_unit *unit, const char *what, cm_slot *out);
/* A duration in microseconds. */
int cm_duration(cm_cc *cc, const cm_aval *v, const char *what, int64_t *us);
cm_var *cm_find_var(cm_cc *cc, const char *name, cm_loc loc, const char *what);
const char *cm_type_name(chasm_type t);
void cm_add_writer(cm_cc *cc, cm_var *v, cm_loc loc, const char *desc, cm_state *state);

void cm_compile_vars(cm_cc *cc);
void cm_compile_states(cm_cc *cc);
void cm_compile_tests(cm_cc *cc);
void cm_compile_actions(cm_cc *cc);
void cm_compile_transitions(cm_cc *cc);
void cm_check_writers(cm_cc *cc);

/* Plugins (cm_plugins.c). */
void cm_load_plugins(cm_cc *cc);
cm_plugin *cm_find_plugin_of(cm_cc *cc, const char *item, int want_test, cm_loc loc, const void **spec);
/* Resolves args against a schema into a new binding in arena a; errors to d. */
cm_binding *cm_bind(cm_cc *cc, cm_arena *a, cm_plugin_version *ver, const char *item_name, const chasm_param_spec *specs,
                    size_t n_specs, const cm_aarg *args, cm_loc item_loc, cm_state *writer_state, bool record_writers);
#endif
