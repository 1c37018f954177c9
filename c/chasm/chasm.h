/* chasm.h: the CHASM engine (Convenient Hierarchical Autonomous State Machine).
 *
 * A manager loads a mission plan once (chasm_load_file), which parses it,
 * loads the plugins it names, checks every parameter and variable and builds
 * every object; then it calls chasm_step() once per cycle with the mission
 * time. The library never reads a clock, never allocates in chasm_step()
 * (except to grow a message buffer to a longer message than it held before) and
 * has no LCM dependency: managers copy message fields into the blackboard with
 * chasm_var_set_*() and publish chasm_status_get() and output variables.
 *
 * The plan language and the semantics are described in docs/chasm.md. */
#ifndef CHASM_H
#define CHASM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "chasm/chasm_plugin.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct chasm_machine chasm_machine;
typedef struct chasm_errors chasm_errors;

/* Same numbers as auv.chasm_status_t.run_state. */
typedef enum {
    CHASM_RUN_LOADED = 0,   /* loaded, not started */
    CHASM_RUN_RUNNING = 1,
    CHASM_RUN_PAUSED = 2,
    CHASM_RUN_DONE = 3,     /* a root state completed with no `next` */
    CHASM_RUN_ABORTED = 4,  /* chasm_abort() and the plan has no abort transition */
    CHASM_RUN_FAILED = 5    /* a failure the plan did not catch */
} chasm_run_state;

typedef enum { CHASM_VAR_INPUT = 0, CHASM_VAR_OUTPUT = 1, CHASM_VAR_LOCAL = 2 } chasm_var_kind;

typedef struct {
    const char *const *plugin_path;   /* directories searched for chasm_NAME.so, NAME.so */
    size_t n_plugin_path;
    /* Parameter overrides (`-D depth=12m`): each value is one value in plan
     * syntax ("12 m", "\"text\"", true), never plan text, and each name must
     * be a parameter the plan declares, with a value of the same kind and
     * unit dimension; anything else is a load error in "<-D name>". */
    const char *const *param_names;
    const char *const *param_values;
    size_t n_params;
    /* Messages from plugins and the engine (state entered, hot plug); may be NULL. */
    void (*log)(void *user, int64_t now_us, const char *state_path, const char *message);
    void *log_user;
    /* chasm_load_string only: folder that relative `include`s start from. */
    const char *base_dir;
    /* A variable stamped more than this ahead of `now` counts as infinitely
     * old (stale) in `age` tests and chasm_ctx age(): no stamp can switch off
     * an `age > X` rule. 0: CHASM_FUTURE_TOLERANCE_US. */
    int64_t future_tolerance_us;
} chasm_options;

/* Time (docs/channels.md, "Time and timestamps"): every time difference the
 * engine computes (elapsed, for, every, after, age) saturates instead of
 * overflowing, so any int64 `now` or stamp is safe. Ages are never negative. */
#define CHASM_FUTURE_TOLERANCE_US INT64_C(1000000)

/* Limits of a plan (docs/chasm.md, "Limits"); going past one is a load error
 * that names it, never a silent cut. */
#define CHASM_STRING_MAX 1023          /* characters of a string value or variable */
#define CHASM_MAX_FILE_BYTES (64 * 1024 * 1024) /* one plan file or plan text */
#define CHASM_MAX_STATE_DEPTH 32       /* levels of nested states (= CHASM_STATUS_MAX_DEPTH) */
#define CHASM_MAX_INCLUDE_DEPTH 16     /* files included inside each other */
#define CHASM_MESSAGE_MAX_BYTES 65536  /* one message of a `messages` variable */
#define CHASM_MESSAGES_DEFAULT_CAPACITY 64   /* `messages` = `messages(64)` */
#define CHASM_MESSAGES_MAX_CAPACITY 4096

/* Load: on any error returns NULL and, if errors != NULL, every error found. */
chasm_machine *chasm_load_file(const char *path, const chasm_options *opt, chasm_errors **errors);
chasm_machine *chasm_load_string(const char *name, const char *text, size_t len,
                                 const chasm_options *opt, chasm_errors **errors);
void chasm_free(chasm_machine *m);

size_t chasm_errors_count(const chasm_errors *e);
/* "file:line:col: error: message", sorted by file, line and column. */
const char *chasm_errors_get(const chasm_errors *e, size_t i);
void chasm_errors_free(chasm_errors *e);

/* Enters the initial root state and its default leaf (entry actions run). */
int chasm_start(chasm_machine *m, int64_t now_us);
/* One cycle: actions by time model, tests, then at most one transition.
 * Returns the run state. Cost depends on the active path only. */
chasm_run_state chasm_step(chasm_machine *m, int64_t now_us);
/* Operator abort: takes the plan's first `abort` transition, or stops the
 * machine (exit actions run) with CHASM_RUN_ABORTED if the plan has none. */
void chasm_abort(chasm_machine *m, int64_t now_us, const char *reason);
void chasm_pause(chasm_machine *m, bool paused);
chasm_run_state chasm_run_state_of(const chasm_machine *m);
const char *chasm_run_state_name(chasm_run_state s);

/* Blackboard. Ids are stable for the life of the machine: look them up once. */
int chasm_var_find(const chasm_machine *m, const char *name);   /* -1 if unknown */
size_t chasm_var_count(const chasm_machine *m);
const char *chasm_var_name(const chasm_machine *m, int id);
chasm_type chasm_var_type(const chasm_machine *m, int id);
chasm_var_kind chasm_var_kind_of(const chasm_machine *m, int id);
const char *chasm_var_unit(const chasm_machine *m, int id);     /* SI unit, "" if none */
/* Setters return 0, or -1 on a bad id, a type mismatch or a string longer
 * than CHASM_STRING_MAX (nothing is written then). utime = time of validity. */
int chasm_var_set_double(chasm_machine *m, int id, double v, int64_t utime);
int chasm_var_set_int(chasm_machine *m, int id, int64_t v, int64_t utime);
int chasm_var_set_bool(chasm_machine *m, int id, bool v, int64_t utime);
int chasm_var_set_string(chasm_machine *m, int id, const char *v, int64_t utime);
double chasm_var_get_double(const chasm_machine *m, int id);   /* ints and bools convert */
int64_t chasm_var_get_int(const chasm_machine *m, int id);
bool chasm_var_get_bool(const chasm_machine *m, int id);
const char *chasm_var_get_string(const chasm_machine *m, int id);
int64_t chasm_var_updated_us(const chasm_machine *m, int id);   /* INT64_MIN: never */

/* Message variables (type `messages`, docs/chasm.md "Message variables").
 * append: the host adds one message (the raw bytes of an encoded message) to
 * the stream of variable id, stamped utime; plugins see it from the next
 * chasm_step on. 0, or -1 (bad id, not a messages variable, more than
 * CHASM_MESSAGE_MAX_BYTES, out of memory: nothing is added). The stream keeps
 * the newest `capacity`; a reader that falls behind loses the oldest (missed).
 * take: the oldest message of the stream the host has not taken yet (posts of
 * an output enter its stream when a cycle ends), NULL when there is none; the
 * bytes stay valid until the next append, chasm_step or chasm_free. Call it
 * after each chasm_step until NULL, or the oldest are lost (counted missed). */
int chasm_messages_append(chasm_machine *m, int id, const void *data, size_t len, int64_t utime);
const void *chasm_messages_take(chasm_machine *m, int id, size_t *len);
typedef struct {
    size_t capacity;
    uint64_t total;      /* messages that entered the stream (appended, or posted at a cycle's end) */
    uint64_t missed;     /* lost by readers that fell more than `capacity` behind (actions and host) */
    uint64_t refused;    /* posts refused: too large, more than `capacity` in a cycle, no memory */
} chasm_messages_info;
int chasm_messages_stats(const chasm_machine *m, int id, chasm_messages_info *out);

/* Introspection, published by managers as auv.chasm_status_t. Pointers stay
 * valid until the next chasm_step/chasm_free. */
#define CHASM_STATUS_MAX_DEPTH 32
#define CHASM_STATUS_MAX_TESTS 16
typedef struct {
    chasm_run_state run_state;
    int64_t cycle;
    int path_len;
    const char *active_path[CHASM_STATUS_MAX_DEPTH];    /* root first: state names */
    double time_in_state_s[CHASM_STATUS_MAX_DEPTH];
    const char *leaf_path;                              /* "mission/survey/leg" */
    int64_t last_transition_us;                         /* INT64_MIN: none yet */
    const char *last_from, *last_to;                    /* full paths of the leaves */
    const char *last_condition;                         /* text, "start", "completed", "abort" */
    int n_tests;
    const char *test_name[CHASM_STATUS_MAX_TESTS];
    bool test_value[CHASM_STATUS_MAX_TESTS];
} chasm_status;
void chasm_status_get(const chasm_machine *m, int64_t now_us, chasm_status *out);

/* Hot plug: load the plugin file so_path (a new version of a plugin the plan
 * uses). Checked like at load; on any error returns -1 with the reason in err
 * and the running mission is untouched. On success actions switch to the new
 * code at the next entry of their state; the old code is unloaded once no
 * active state uses it. */
int chasm_hotplug(chasm_machine *m, const char *so_path, char *err, size_t errlen);
/* Number of plugin code versions currently loaded (for tests and status). */
int chasm_plugin_versions_loaded(const chasm_machine *m);
/* 1 if the loaded plan names plugin `name` in a `use`. */
int chasm_uses_plugin(const chasm_machine *m, const char *name);

/* Plugin files. Every loader (`use` in a plan, hot plug, `chasm describe`, a
 * manager's upload) opens a file the same way: a regular file of at most
 * 64 MiB, its ELF structure checked on the bytes read (cm_elf_check.h), a
 * private copy loaded first in a probe process (a file that crashes, exits or
 * hangs for 2 s there is refused), then ABI, symbol and schema checked. A
 * plugin name is 1-63 characters of a-z, 0-9 and _, beginning with a letter. */
#define CHASM_PLUGIN_NAME_MAX 63
#define CHASM_PLUGIN_NAME_MAX_TEXT "63"
int chasm_plugin_name_check(const char *name, char *err, size_t errlen);
/* Opens one plugin file on its own, for tools and uploads; if name is not
 * NULL the file must hold that plugin. NULL with the reason in err. */
typedef struct chasm_plugin_file chasm_plugin_file;
chasm_plugin_file *chasm_plugin_file_open(const char *path, const char *name, char *err, size_t errlen);
const chasm_plugin_descriptor *chasm_plugin_file_descriptor(const chasm_plugin_file *f);
void chasm_plugin_file_close(chasm_plugin_file *f);

/* Graphviz DOT of states, default children (bold), default next (dashed) and
 * transitions (labelled with their conditions). */
void chasm_write_dot(const chasm_machine *m, FILE *out);

/* Counts, for tools and benchmarks. */
size_t chasm_state_count(const chasm_machine *m);
size_t chasm_test_count(const chasm_machine *m);

#ifdef __cplusplus
}
#endif
#endif
