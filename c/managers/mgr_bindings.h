/* Bindings: which LCM channel feeds or carries each blackboard prefix.
 *
 * A binding file has one line per message:
 *     input   nav       ${VEHICLE}.NAV        nav_solution_t
 *     input   gps       ${VEHICLE}.GPS        gps_fix_t   optional
 *     output  setpoint  ${VEHICLE}.SETPOINT   setpoint_t
 * and may take in the lines of shared files (resolved relative to itself):
 *     include "shared/sensors.bind"
 * A plan variable `nav.depth_m` then reads field depth_m of every
 * nav_solution_t on AUV1.NAV; `setpoint.heading_rad` is written into the
 * setpoint_t published each cycle. Fields are found through the type table
 * generated from lcmtypes/ (common/field_path.h): no per-field code. */
#ifndef MGR_BINDINGS_H
#define MGR_BINDINGS_H

#include <lcm/lcm.h>

#include "chasm/chasm.h"
#include "common/field_path.h"
#include "common/lcm_rx.h"
#include "common/time_policy.h"
#include "managers/mgr_errors.h"
#include "managers/mgr_held.h"
#include "managers/mgr_limits.h"

typedef struct {
    int var;                /* blackboard id */
    chasm_type var_type;
    field_ref_t field;
} mgr_var_binding;

typedef struct {
    int is_output;
    int optional;           /* input the plan may start without (`optional`) */
    int on_change;          /* output published when it changed, else once a second (`on_change`) */
    char *prefix;           /* any length: plan names have no limit */
    char channel[MGR_MAX_CHANNEL + 1];
    const auv_type_entry_t *type;
    int line;               /* in the binding file, for messages */
    char *file;             /* that file (an included one, or the one given) */
    mgr_var_binding *vars;
    int n_vars;
    /* inputs */
    rx_sub_t *sub;
    tp_input order;         /* newest accepted utime: time rule checks */
    struct mgr_bindings *owner;
    /* outputs: a struct filled each cycle */
    void *scratch;
    field_ref_t utime, vehicle;
    int has_utime, has_vehicle;
    /* A binding whose prefix is a plan variable of type `messages` carries
     * whole messages: inputs are appended to its stream as received (raw
     * bytes), posts to an output are checked to decode and published in order
     * after the cycle. -1: a binding of fields. */
    int stream_var;
    uint64_t messages_in;       /* appended to the stream */
    uint64_t posts_refused;     /* posted bytes that do not decode as the type */
    uint64_t messages_out;      /* published */
    /* `on_change`: the last encoding published, its utime zeroed, and when */
    uint8_t *last_sent;
    int last_sent_len;
    int64_t last_sent_us;
} mgr_message_binding;

typedef struct mgr_bindings {
    mgr_message_binding *msgs;
    int n_msgs;
    chasm_machine *machine; /* the machine inputs are copied into */
    const char *vehicle;
    uint64_t inputs_applied;
    /* The receiver's clock inputs are judged against (docs/channels.md,
     * "Time and timestamps"); set by the manager before subscribing. */
    const tp_clock *clock;
    /* Nonzero while the clock is a lockstep clock: inputs stamped after it
     * wait for it (mgr_held.h). */
    const int *lockstep;
    mgr_held held;
    int64_t future_tol_us;
    const char *who;        /* manager name, for the first-drop log lines */
    tp_counts time_drops;   /* per tp_reason */
    uint64_t range_drops;   /* a value that does not fit its variable (or a message over CHASM_MESSAGE_MAX_BYTES) */
} mgr_bindings;

/* Message variables' counters, summed over the bindings of streams:
 * messages appended to input streams, messages lost by slow readers (any
 * stream), posts refused (by the engine: too large or too many in a cycle;
 * by the manager: not an encoded message of the bound type), published. */
typedef struct {
    uint64_t in, missed, refused, out;
    int n_streams;
} mgr_stream_counts;
mgr_stream_counts mgr_bindings_stream_counts(const mgr_bindings *b);

/* Parse the binding file (with ${VEHICLE} expanded) and bind every input and
 * output variable of the plan. Errors go to stderr as file:line:col: message;
 * returns the number of errors (0 = ready). */
int mgr_bindings_load(mgr_bindings *b, const char *path, const char *vehicle, chasm_machine *m, mgr_errors *errs);
/* mgr_bindings_load from text (the fuzzer uses it). */
int mgr_bindings_load_text(mgr_bindings *b, const char *path, const char *text, size_t len, const char *vehicle,
                           chasm_machine *m, mgr_errors *errs);
/* Only the file's syntax (and the files it includes), nothing bound
 * (mgr_bind_parse.c, mgr_bind_files.c). Return the number of errors. */
int mgr_bindings_parse_file(mgr_bindings *b, const char *path, const char *vehicle, mgr_errors *errs);
int mgr_bindings_parse_text(mgr_bindings *b, const char *path, const char *text, size_t len, const char *vehicle,
                            mgr_errors *errs);
/* The handler of every input subscription (mgr_inputs.c); user is the binding. */
void mgr_input_received(const char *channel, const void *msg, int64_t recv_utime, void *user);
/* Subscribe to every input channel; messages then update the blackboard. */
int mgr_bindings_subscribe(mgr_bindings *b, lcm_t *lcm);
/* Publish every output message with the current output variables. */
void mgr_bindings_publish(mgr_bindings *b, lcm_t *lcm, int64_t now_us);
uint64_t mgr_bindings_decode_errors(const mgr_bindings *b);
/* True once every bound input channel not marked `optional` has delivered a
 * message: a plan does not start on a blackboard it has never seen filled. */
int mgr_bindings_inputs_ready(const mgr_bindings *b);
/* Judge what inputs held before the clock existed: a value from the future
 * of `now` is counted as such and its input accepts newer messages again
 * (libchasm already treats it as stale). Cheap: call every cycle. */
void mgr_bindings_recheck(mgr_bindings *b, int64_t now);
/* Apply the held inputs whose step's clock has come (mgr_held.h): call after
 * the cycle of each clock, before the next clock can be handled. */
void mgr_bindings_release_held(mgr_bindings *b);
void mgr_bindings_free(mgr_bindings *b, lcm_t *lcm);

#endif
