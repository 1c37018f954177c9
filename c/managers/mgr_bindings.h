/* Bindings: which LCM channel feeds or carries each blackboard prefix.
 *
 * A binding file has one line per message:
 *     input   nav       ${VEHICLE}.NAV        nav_solution_t
 *     input   gps       ${VEHICLE}.GPS        gps_fix_t   optional
 *     output  setpoint  ${VEHICLE}.SETPOINT   setpoint_t
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

typedef struct {
    int var;                /* blackboard id */
    chasm_type var_type;
    field_ref_t field;
} mgr_var_binding;

typedef struct {
    int is_output;
    int optional;           /* input the plan may start without (`optional`) */
    char prefix[64];
    char channel[128];
    const auv_type_entry_t *type;
    int line;               /* in the binding file, for messages */
    mgr_var_binding *vars;
    int n_vars;
    /* inputs */
    rx_sub_t *sub;
    struct mgr_bindings *owner;
    /* outputs: a struct filled each cycle */
    void *scratch;
    field_ref_t utime, vehicle;
    int has_utime, has_vehicle;
} mgr_message_binding;

typedef struct mgr_bindings {
    mgr_message_binding *msgs;
    int n_msgs;
    chasm_machine *machine; /* the machine inputs are copied into */
    const char *vehicle;
    uint64_t inputs_applied;
} mgr_bindings;

/* Parse the binding file (with ${VEHICLE} expanded) and bind every input and
 * output variable of the plan. Errors go to stderr as file:line:col: message;
 * returns the number of errors (0 = ready). */
int mgr_bindings_load(mgr_bindings *b, const char *path, const char *vehicle, chasm_machine *m);
/* Subscribe to every input channel; messages then update the blackboard. */
int mgr_bindings_subscribe(mgr_bindings *b, lcm_t *lcm);
/* Publish every output message with the current output variables. */
void mgr_bindings_publish(mgr_bindings *b, lcm_t *lcm, int64_t now_us);
uint64_t mgr_bindings_decode_errors(const mgr_bindings *b);
/* True once every bound input channel not marked `optional` has delivered a
 * message: a plan does not start on a blackboard it has never seen filled. */
int mgr_bindings_inputs_ready(const mgr_bindings *b);
void mgr_bindings_free(mgr_bindings *b, lcm_t *lcm);

#endif
