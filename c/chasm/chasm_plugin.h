/* chasm_plugin.h: everything a behavior or test-handler plugin needs.
 *
 * A plugin is a shared object that exports ONE symbol, `chasm_plugin`, of type
 * chasm_plugin_descriptor (use CHASM_PLUGIN_EXPORT). It describes the plugin's
 * behaviors and test handlers (one table of each, see "Registration" below)
 * and, for each, a schema of parameters: the Loader checks every value of a
 * plan against that schema (type, unit, range, required) before a mission
 * starts, so a behavior never has to validate them.
 *
 * Plugins see CHASM only through chasm_ctx and the inline accessors below, which
 * call through a function table: a plugin links against nothing and does not
 * depend on the engine's internal layout. Values are SI (m, s, rad, m/s, rad/s).
 *
 * Slots: a behavior's parameters are numbered in the order of its schema; the
 * same index is used to read a parameter (chasm_param_*) or, for a
 * CHASM_READS/CHASM_WRITES entry, the blackboard variable the plan bound to it
 * (chasm_read_* / chasm_write_*). Reading a slot of the wrong type gives 0/"".
 * Write schemas with the CHASM_PARAM_* / CHASM_READ* / CHASM_WRITE* builders
 * below, indexed by the slot enum, so the two cannot drift apart. */
#ifndef CHASM_PLUGIN_H
#define CHASM_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever any struct below changes layout; the Loader refuses others.
 * 2: message variables (CHASM_MESSAGES, next_message, post_message).
 * 3: chasm_param_spec.flags (CHASM_SPEC_NO_DEFAULT), host api param_given. */
#define CHASM_PLUGIN_ABI 3
#define CHASM_PLUGIN_SYMBOL "chasm_plugin"

/* CHASM_MESSAGES: a variable that is a stream of whole messages (LCM-encoded
 * bytes of its binding's type), not a value: plans declare it
 * `input contacts : messages` / `output modem_tx : messages`. Every message
 * that arrives is kept for every reader (nothing is overwritten by the next
 * one), so a behavior sees each contact, each frame, once. */
typedef enum { CHASM_DOUBLE = 0, CHASM_INT = 1, CHASM_BOOL = 2, CHASM_STRING = 3, CHASM_MESSAGES = 4 } chasm_type;

/* What a schema entry is: a constant parameter, or a blackboard variable the
 * behavior reads or writes (the one-writer rule covers CHASM_WRITES slots). */
typedef enum { CHASM_PARAM = 0, CHASM_READS = 1, CHASM_WRITES = 2 } chasm_slot_kind;

typedef enum { CHASM_RUNNING = 0, CHASM_DONE = 1, CHASM_FAILED = 2 } chasm_status_code;

typedef struct {
    const char *name;        /* as written in the plan: goto(north = 10 m) */
    chasm_slot_kind kind;
    chasm_type type;
    const char *unit;        /* SI unit: "m", "s", "rad", "m/s", "rad/s", "Hz", "" */
    int required;            /* 1: the plan must give it (PARAM) or bind it (READS/WRITES) */
    double def_number;       /* default of an optional DOUBLE/INT/BOOL param */
    const char *def_string;  /* default of an optional STRING param; for READS/WRITES
                                the default variable name, e.g. "setpoint.heading" */
    int has_range;           /* 1: min <= value <= max is checked at load */
    double min, max;
    const char *doc;         /* one line, shown by `chasm describe` */
    unsigned flags;          /* CHASM_SPEC_* (ABI 3); the Loader refuses bits it does not know */
} chasm_param_spec;

/* An optional CHASM_PARAM without a default (one of two forms, a box or a
 * polygon; a value that overrides a computed one): when the plan leaves it
 * out it reads as 0/"" and chasm_param_given() says so. Not with required. */
#define CHASM_SPEC_NO_DEFAULT 1u

/* Schema builders. Index each entry by its slot so that a slot enum and its
 * table cannot drift apart; a slot left without an entry is a hole (NULL
 * name) that the Loader refuses, naming the plugin and behavior:
 *
 *   enum { DEPTH, GAIN, OUT, N_SLOTS };
 *   static const chasm_param_spec params[N_SLOTS] = {
 *       [DEPTH] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("depth", "m", 0, 300, "target depth"),
 *       [GAIN] = CHASM_PARAM_DOUBLE_RANGE("gain", "", 0.5, 0, 10, "filter gain [1/s]"),
 *       [OUT] = CHASM_WRITE("out", CHASM_DOUBLE, "m", "setpoint.depth_m", "depth setpoint"),
 *   };
 *
 * PARAM: a constant of the plan. REQUIRED: the plan must give it; otherwise
 * DEF is its default; _RANGE: min <= value <= max is checked at load.
 * READ/WRITE: a variable, VAR its default (NULL: none; the plan may bind one),
 * REQUIRED: the plan must bind one. A combination not listed here is written
 * as a designated initializer of its own. Two entries for one slot are a
 * compile error under -Werror (-Wextra's -Woverride-init). */
/* Members in declaration order (what C++20 also accepts). */
#define CHASM_SPEC_(KIND, TYPE, NAME, UNIT) .name = (NAME), .kind = (KIND), .type = (TYPE), .unit = (UNIT)
#define CHASM_RANGE_(MIN, MAX) .has_range = 1, .min = (MIN), .max = (MAX)

#define CHASM_PARAM_DOUBLE(NAME, UNIT, DEF, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_DOUBLE, NAME, UNIT), .def_number = (DEF), .doc = (DOC)}
#define CHASM_PARAM_DOUBLE_RANGE(NAME, UNIT, DEF, MIN, MAX, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_DOUBLE, NAME, UNIT), .def_number = (DEF), CHASM_RANGE_(MIN, MAX), .doc = (DOC)}
#define CHASM_PARAM_REQUIRED_DOUBLE(NAME, UNIT, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_DOUBLE, NAME, UNIT), .required = 1, .doc = (DOC)}
#define CHASM_PARAM_REQUIRED_DOUBLE_RANGE(NAME, UNIT, MIN, MAX, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_DOUBLE, NAME, UNIT), .required = 1, CHASM_RANGE_(MIN, MAX), .doc = (DOC)}
#define CHASM_PARAM_INT(NAME, DEF, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_INT, NAME, ""), .def_number = (DEF), .doc = (DOC)}
#define CHASM_PARAM_INT_RANGE(NAME, DEF, MIN, MAX, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_INT, NAME, ""), .def_number = (DEF), CHASM_RANGE_(MIN, MAX), .doc = (DOC)}
#define CHASM_PARAM_REQUIRED_INT_RANGE(NAME, MIN, MAX, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_INT, NAME, ""), .required = 1, CHASM_RANGE_(MIN, MAX), .doc = (DOC)}
#define CHASM_PARAM_BOOL(NAME, DEF, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_BOOL, NAME, ""), .def_number = (DEF), .doc = (DOC)}
#define CHASM_PARAM_REQUIRED_BOOL(NAME, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_BOOL, NAME, ""), .required = 1, .doc = (DOC)}
#define CHASM_PARAM_STRING(NAME, DEF, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_STRING, NAME, ""), .def_string = (DEF), .doc = (DOC)}
#define CHASM_PARAM_REQUIRED_STRING(NAME, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, CHASM_STRING, NAME, ""), .required = 1, .doc = (DOC)}
/* Optional, no default: ask chasm_param_given() before using the value. */
#define CHASM_PARAM_OPTIONAL(NAME, TYPE, UNIT, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, TYPE, NAME, UNIT), .doc = (DOC), .flags = CHASM_SPEC_NO_DEFAULT}
#define CHASM_PARAM_OPTIONAL_RANGE(NAME, TYPE, UNIT, MIN, MAX, DOC) \
    {CHASM_SPEC_(CHASM_PARAM, TYPE, NAME, UNIT), CHASM_RANGE_(MIN, MAX), .doc = (DOC), .flags = CHASM_SPEC_NO_DEFAULT}

#define CHASM_READ(NAME, TYPE, UNIT, VAR, DOC) \
    {CHASM_SPEC_(CHASM_READS, TYPE, NAME, UNIT), .def_string = (VAR), .doc = (DOC)}
#define CHASM_READ_REQUIRED(NAME, TYPE, UNIT, DOC) \
    {CHASM_SPEC_(CHASM_READS, TYPE, NAME, UNIT), .required = 1, .doc = (DOC)}
#define CHASM_WRITE(NAME, TYPE, UNIT, VAR, DOC) \
    {CHASM_SPEC_(CHASM_WRITES, TYPE, NAME, UNIT), .def_string = (VAR), .doc = (DOC)}
#define CHASM_WRITE_REQUIRED(NAME, TYPE, UNIT, DOC) \
    {CHASM_SPEC_(CHASM_WRITES, TYPE, NAME, UNIT), .required = 1, .doc = (DOC)}

typedef struct chasm_ctx chasm_ctx;

/* The engine's side of the context; plugins use the inline helpers instead. */
typedef struct {
    double (*param_double)(const chasm_ctx *, int slot);
    int64_t (*param_int)(const chasm_ctx *, int slot);
    int (*param_bool)(const chasm_ctx *, int slot);
    const char *(*param_string)(const chasm_ctx *, int slot);
    double (*read_double)(const chasm_ctx *, int slot);
    int64_t (*read_int)(const chasm_ctx *, int slot);
    int (*read_bool)(const chasm_ctx *, int slot);
    const char *(*read_string)(const chasm_ctx *, int slot);
    double (*age_s)(const chasm_ctx *, int slot);   /* since the variable's last update */
    void (*write_double)(chasm_ctx *, int slot, double v);
    void (*write_int)(chasm_ctx *, int slot, int64_t v);
    void (*write_bool)(chasm_ctx *, int slot, int v);
    void (*write_string)(chasm_ctx *, int slot, const char *v);
    void (*log)(chasm_ctx *, const char *message);
    /* Message variables (ABI 2). next_message: for a CHASM_READS slot of type
     * CHASM_MESSAGES, the oldest message this action has not yet taken (each
     * action instance has its own place in the stream), or NULL when it has
     * seen them all; *len is set to its size. The bytes stay valid until the
     * action's call returns. Messages an action was too slow for (the
     * variable keeps the newest `capacity`) are counted as missed, never
     * handed out twice. post_message: for a CHASM_WRITES slot of type
     * CHASM_MESSAGES, queue the bytes (an encoded message of the bound type)
     * for publishing after this cycle, in order. Returns 0, or -1 when it is
     * refused (too large, queue full: counted in the manager's status). */
    const void *(*next_message)(chasm_ctx *, int slot, size_t *len);
    int (*post_message)(chasm_ctx *, int slot, const void *data, size_t len);
    /* ABI 3. param_given: 1 when the plan gave this CHASM_PARAM slot a value
     * (a default is not given), or a variable is bound to this
     * CHASM_READS/CHASM_WRITES slot (by the plan or by its default); else 0. */
    int (*param_given)(const chasm_ctx *, int slot);
} chasm_host_api;

/* Handed to every call. Read-only for the plugin except through the api. */
struct chasm_ctx {
    const chasm_host_api *api;
    int64_t now_us;          /* mission time of this cycle */
    double dt_s;             /* since this action last ran (0 at its first run) */
    double time_in_state_s;  /* since its state was entered */
    const char *state_path;  /* "mission/survey/leg", for messages */
    void *engine;            /* opaque */
};

static inline double chasm_param_double(const chasm_ctx *c, int s) { return c->api->param_double(c, s); }
static inline int64_t chasm_param_int(const chasm_ctx *c, int s) { return c->api->param_int(c, s); }
static inline int chasm_param_bool(const chasm_ctx *c, int s) { return c->api->param_bool(c, s); }
static inline const char *chasm_param_string(const chasm_ctx *c, int s) { return c->api->param_string(c, s); }
static inline double chasm_read_double(const chasm_ctx *c, int s) { return c->api->read_double(c, s); }
static inline int64_t chasm_read_int(const chasm_ctx *c, int s) { return c->api->read_int(c, s); }
static inline int chasm_read_bool(const chasm_ctx *c, int s) { return c->api->read_bool(c, s); }
static inline const char *chasm_read_string(const chasm_ctx *c, int s) { return c->api->read_string(c, s); }
static inline double chasm_age_s(const chasm_ctx *c, int s) { return c->api->age_s(c, s); }
static inline void chasm_write_double(chasm_ctx *c, int s, double v) { c->api->write_double(c, s, v); }
static inline void chasm_write_int(chasm_ctx *c, int s, int64_t v) { c->api->write_int(c, s, v); }
static inline void chasm_write_bool(chasm_ctx *c, int s, int v) { c->api->write_bool(c, s, v); }
static inline void chasm_write_string(chasm_ctx *c, int s, const char *v) { c->api->write_string(c, s, v); }
static inline void chasm_log(chasm_ctx *c, const char *m) { c->api->log(c, m); }
static inline const void *chasm_next_message(chasm_ctx *c, int s, size_t *len) { return c->api->next_message(c, s, len); }
static inline int chasm_post_message(chasm_ctx *c, int s, const void *d, size_t n) { return c->api->post_message(c, s, d, n); }
static inline int chasm_param_given(const chasm_ctx *c, int s) { return c->api->param_given(c, s); }

/* A behavior: per-instance state of state_size bytes, zeroed before start().
 * start() runs when its state is entered (return non-zero to fail), step() when
 * its time model says so, stop() when the state is left. Any may be NULL except
 * step. step() returns CHASM_DONE to complete its state (periodic actions) or
 * CHASM_FAILED to raise `failed`, which the plan can catch. */
typedef struct {
    const char *name;
    const char *doc;
    const chasm_param_spec *params;
    size_t n_params;
    size_t state_size;
    int (*start)(chasm_ctx *, void *state);
    chasm_status_code (*step)(chasm_ctx *, void *state);
    void (*stop)(chasm_ctx *, void *state);
} chasm_behavior_spec;

/* A test handler: evaluate() returns 1 when its criterion holds this cycle.
 * The engine adds `for at least T` itself. Params and slots as for behaviors. */
typedef struct {
    const char *name;
    const char *doc;
    const chasm_param_spec *params;
    size_t n_params;
    int (*evaluate)(chasm_ctx *);
} chasm_test_spec;

typedef struct {
    uint32_t abi_version;    /* CHASM_PLUGIN_ABI */
    uint32_t struct_size;    /* sizeof(chasm_plugin_descriptor) */
    const char *name;        /* matches `use NAME` in plans and the file chasm_NAME.so */
    const char *version;     /* free text, "1.2.0" */
    const chasm_behavior_spec *behaviors;
    size_t n_behaviors;
    const chasm_test_spec *tests;
    size_t n_tests;
} chasm_plugin_descriptor;

/* Elements of an array; a pointer given instead (whose count this is not)
 * is a compile error where the compiler can tell (GCC, Clang; C only). */
#if defined(__GNUC__) && !defined(__cplusplus)
#define CHASM_NOT_POINTER_(a) \
    (0 * sizeof(struct { int an_array_: 1 - 2 * __builtin_types_compatible_p(__typeof__(a), __typeof__(&(a)[0])); }))
#else
#define CHASM_NOT_POINTER_(a) 0
#endif
#define CHASM_COUNT(a) (sizeof(a) / sizeof((a)[0]) + CHASM_NOT_POINTER_(a))

/* Registration: the one way a plugin registers its behaviors and test
 * handlers. Each plugin has one table of behaviors and one of test handlers,
 * `static const` arrays in its <plugin>_plugin.c, each entry a designated
 * initializer; the schema is given with CHASM_SCHEMA and the tables with
 * CHASM_BEHAVIORS / CHASM_TESTS in CHASM_PLUGIN_EXPORT:
 *
 *   static const chasm_behavior_spec behaviors[] = {
 *       {.name = "ramp_depth", .doc = "ramp the depth setpoint", CHASM_SCHEMA(params),
 *        .state_size = sizeof(state_t), .step = step},
 *   };
 *   static const chasm_test_spec tests[] = {
 *       {.name = "deep", .doc = "deeper than limit", CHASM_SCHEMA(deep_params), .evaluate = deep},
 *   };
 *   CHASM_PLUGIN_EXPORT("depth_tools", "1.0.0", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));
 *
 * Why this form: named fields cannot be swapped silently (name and doc are
 * both strings, n_params and state_size both sizes), optional members (doc,
 * state_size, start, stop) are left out rather than padded with NULL and 0,
 * and an entry survives a field added at an ABI bump; a macro of positional
 * arguments (a BEHAVIOR(...) of a plugin's own, or one here) would bring back
 * the positional problem. Why one table written out in one file: the
 * descriptor takes a contiguous array, and C cannot build one at compile time
 * from spec objects defined in other files (copying them in at load time
 * needs a constructor and a writable table); each behavior file therefore
 * exports its schema and entry points (hidden), and the table names them. The
 * only helpers are for the pairs of a pointer and its count, which must not
 * drift apart. tests/chasm/test_plugin_registration.py holds every plugin,
 * test plugin and doc example to this. Members in declaration order (C++20
 * too). */
#define CHASM_SCHEMA(PARAMS) .params = (PARAMS), .n_params = CHASM_COUNT(PARAMS)
#define CHASM_BEHAVIORS(TABLE) .behaviors = (TABLE), .n_behaviors = CHASM_COUNT(TABLE)
#define CHASM_TESTS(TABLE) .tests = (TABLE), .n_tests = CHASM_COUNT(TABLE)

/* Defines the exported descriptor of the plugin NAME (`use NAME`), VERSION
 * free text, then CHASM_BEHAVIORS(table) and/or CHASM_TESTS(table), in that
 * order. The ABI version and struct size are filled in here, so a plugin
 * always says what it was built against. */
#define CHASM_PLUGIN_EXPORT(NAME, VERSION, ...)                                                      \
    __attribute__((visibility("default"))) const chasm_plugin_descriptor chasm_plugin = {            \
        .abi_version = CHASM_PLUGIN_ABI, .struct_size = (uint32_t)sizeof(chasm_plugin_descriptor), \
        .name = (NAME), .version = (VERSION), __VA_ARGS__}

/* Optional: limits of a plan's values that the schema cannot state (a
 * polygon's vertex count, a list's length). A plugin may define
 *
 *   CHASM_PLUGIN_CHECK(check);
 *   static int check(const char *item, const chasm_ctx *c, int *slot, char *why, size_t whylen);
 *
 * The Loader calls it at load (and at a hot plug) for every behavior and test
 * handler `item` of this plugin the plan uses, with the plan's parameters
 * readable through chasm_param_*; variables read as 0 and writes are ignored.
 * Return 0 if the values are usable; otherwise set *slot to the parameter at
 * fault (or -1 for the item as a whole) and write the reason to why: the plan
 * fails to load with "file:line:col: error: parameter 'p' of 'item': why".
 * An optional symbol, not part of the descriptor: the ABI is unchanged. */
#define CHASM_PLUGIN_CHECK_SYMBOL "chasm_plugin_check"
typedef int (*chasm_plugin_check_fn)(const char *item, const chasm_ctx *c, int *slot, char *why, size_t whylen);
#define CHASM_PLUGIN_CHECK(FN)                                                                              \
    static int FN(const char *, const chasm_ctx *, int *, char *, size_t);                                 \
    __attribute__((visibility("default"))) int chasm_plugin_check(const char *item, const chasm_ctx *c, int *slot, \
                                                                  char *why, size_t whylen);                 \
    int chasm_plugin_check(const char *item, const chasm_ctx *c, int *slot, char *why, size_t whylen)          \
    {                                                                                                       \
        return FN(item, c, slot, why, whylen);                                                              \
    }

#ifdef __cplusplus
}
#endif
#endif
