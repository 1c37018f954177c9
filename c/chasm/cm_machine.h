/* The compiled machine: every object is built by the Loader, in one arena,
 * linked by pointers and indices so chasm_step() does no lookups by name and
 * no allocation. Shared by the compile passes, the runtime and the tools. */
#ifndef CM_MACHINE_H
#define CM_MACHINE_H
#include <stdbool.h>
#include <stdint.h>

#include "chasm/chasm.h"
#include "chasm/cm_arena.h"
#include "chasm/cm_ast.h"
#include "chasm/cm_map.h"
#include "chasm/cm_stream.h"

#define CM_NEVER INT64_MIN

/* now - since in microseconds, saturated: no signed overflow for any pair. */
static inline int64_t cm_span_us(int64_t now, int64_t since)
{
    int64_t r;
    if (__builtin_sub_overflow(now, since, &r)) return since < 0 ? INT64_MAX : INT64_MIN;
    return r;
}
/* a + b saturated. */
static inline int64_t cm_add_us(int64_t a, int64_t b)
{
    int64_t r;
    if (__builtin_add_overflow(a, b, &r)) return b > 0 ? INT64_MAX : INT64_MIN;
    return r;
}

typedef struct cm_var {
    const char *name;
    chasm_type type;
    chasm_var_kind kind;
    const cm_unit *unit;        /* declared unit; values are stored in it */
    double d;
    int64_t i;
    bool b;
    char *s;
    size_t s_cap;
    int64_t updated_us;
    bool has_value;             /* initialised or written: tests on a variable without value are false */
    cm_loc loc;
    int index;
    cm_stream *stream;          /* CHASM_MESSAGES only */
} cm_var;

/* One resolved schema slot of an action or test: a constant or a variable. */
typedef struct {
    double d;
    int64_t i;
    int b;
    const char *s;
    cm_var *var;
    uint64_t next_msg;          /* a READS messages slot: this action's place in the stream */
    bool given;                 /* a PARAM slot: the plan gave it (chasm_param_given) */
} cm_slot;

struct cm_plugin;

/* One loaded file of a plugin (cm_plugin_file.h: checked, probed, and loaded
 * from a private copy so two versions from one path get distinct handles). */
typedef struct cm_plugin_version {
    struct cm_plugin *plugin;
    void *dl;
    const chasm_plugin_descriptor *desc;
    chasm_plugin_check_fn check; /* the plugin's own limits of plan values, or NULL */
    int serial;                 /* 1, 2, ... per plugin */
    int refs;                   /* bindings pointing here (current and pending) */
    bool retired;               /* a newer version is current */
    cm_arena arena;             /* bindings made against this version */
    struct cm_plugin_version *next_loaded;
} cm_plugin_version;

typedef struct cm_plugin {
    const char *name;
    const char *file;
    cm_loc loc;
    cm_plugin_version *current;
    int n_versions;
} cm_plugin;

/* An action's or test's use of plugin code, for one code version. */
typedef struct cm_binding {
    cm_plugin_version *ver;
    const chasm_behavior_spec *beh;
    const chasm_test_spec *test;
    const chasm_param_spec *specs;
    int n_slots;
    cm_slot *slots;
    void *inst;
    size_t inst_size;
} cm_binding;

typedef enum { ACT_SET, ACT_PLUGIN } cm_action_kind;

typedef struct cm_action {
    struct cm_state *state;
    cm_action_kind kind;
    cm_time_model tm;
    int64_t period_us;
    const char *text;           /* "goto", "set setpoint.depth" */
    cm_loc loc;
    const cm_aaction *ast;      /* kept for re-binding on hot plug */
    /* ACT_SET */
    cm_var *var;
    cm_slot value;
    /* ACT_PLUGIN */
    cm_binding *cur, *pending;
    cm_binding *pending_new;    /* hot plug in progress */
    /* runtime */
    int64_t next_due, last_run;
    bool fired, started;
} cm_action;

typedef struct cm_test {
    const char *name;
    struct cm_state *state;     /* NULL: a global test */
    cm_crit_kind kind;
    cm_cmp op;
    cm_var *var;
    double value, tol;          /* in the variable's unit; durations in s */
    bool has_tol, angle;        /* angle: differences wrap to [-pi, pi] */
    const char *sval;
    int64_t hold_us;
    cm_binding *cur, *pending, *pending_new;
    const cm_atest *ast;
    cm_loc loc;
    /* runtime */
    bool value_now;
    int64_t true_since;
} cm_test;

typedef enum { CO_TEST, CO_DONE, CO_FAILED, CO_ELAPSED, CO_TRUE, CO_FALSE, CO_AND, CO_OR, CO_NOT } cm_op;

typedef struct {
    uint8_t op, cmp;
    int32_t arg;
    int64_t t_us;
    struct cm_test *test;
} cm_cop;

typedef struct cm_trans {
    struct cm_state *owner;     /* NULL: a root-level abort */
    cm_cop *code;
    int n_code;
    struct cm_state *target;
    cm_history history;
    const char *text;
    cm_test **refs;             /* tests named in the condition, for status */
    int n_refs;
    cm_loc loc;
} cm_trans;

typedef struct cm_state {
    const char *name, *path;
    int index, depth;
    struct cm_state *parent, *first_child, *next_sibling, *default_child, *next;
    bool next_done;
    bool handles_done;          /* a `when` of its own tests `done`: completion stays here */
    cm_test *tests;
    int n_tests;
    cm_action *actions;
    int n_actions;
    cm_trans *trans;
    int n_trans;
    cm_loc loc;
    const cm_astate *ast;
    /* runtime */
    int64_t entered_us;
    struct cm_state *history_child;
    bool done, failed;         /* failed: its own action failed, or an active descendant's */
    bool self_failed;          /* its own action failed (since entry) */
} cm_state;

struct chasm_machine {
    cm_arena arena;
    const char *plan_name;
    cm_state *states;
    int n_states;
    cm_state *initial;
    cm_var *vars;
    int n_vars;
    cm_map var_map;
    cm_test *globals;
    int n_globals;
    cm_trans *aborts;
    int n_aborts;
    size_t n_tests_total;
    cm_plugin *plugins;
    int n_plugins;
    cm_plugin_version *loaded;  /* every version still loaded */
    cm_stream *streams;         /* of the messages variables (malloc'd: message buffers grow) */
    cm_aplan *plan;             /* the syntax tree, kept to re-bind actions on hot plug */
    cm_map param_map;           /* name -> cm_aparam* (the winning definition) */
    long n_lines;
    chasm_options opt;
    /* runtime */
    cm_state *path[CHASM_STATUS_MAX_DEPTH];
    int path_len;
    chasm_run_state run;
    int64_t cycle, now, last_us, start_us;
    char abort_text[160];
    const cm_state *last_from, *last_to;
    const char *last_cond;
    const cm_trans *last_trans;
    bool last_vals[CHASM_STATUS_MAX_TESTS];
};

/* Runtime entry points used across files. */
extern const chasm_host_api cm_host_api;
void cm_binding_release(chasm_machine *m, cm_binding *b);
/* At an entry or exit of its state a use takes the binding a hot plug left
 * pending (cm_hotplug.c); the one it replaces is released. */
void cm_binding_adopt_pending(chasm_machine *m, cm_binding **cur, cm_binding **pending);
void cm_plugins_unload_all(chasm_machine *m);
/* One plugin file as a new code version (cm_plugins.c); NULL with err set. */
cm_plugin_version *cm_plugin_version_open(chasm_machine *m, const char *path, char *err, size_t errlen);
void cm_plugin_version_unload(chasm_machine *m, cm_plugin_version *v);
void cm_stop_all(chasm_machine *m);

/* What plugin callbacks see behind chasm_ctx.engine. */
typedef struct {
    chasm_ctx c;
    chasm_machine *m;
    cm_binding *b;
} cm_ext;
/* Age of a value stamped `stamp` at `now` in seconds: never negative;
 * INFINITY when never written or stamped more than the future tolerance
 * ahead of now (a stamp from the future must not keep a value fresh). */
double cm_age_s(const chasm_machine *m, int64_t stamp, int64_t now);
void cm_log(chasm_machine *m, const char *path, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
#endif
