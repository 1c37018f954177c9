/* How a received input reaches the blackboard: the time rule, the range
 * checks, and in lockstep the wait of an input that came ahead of its clock
 * (mgr_held.h). The bindings themselves (files, subscriptions, outputs) are
 * mgr_bindings.c. */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "managers/mgr_bindings.h"

/* Does every bound value of this message fit its variable? An integer
 * outside int64 (or NaN) and a string longer than a string variable holds
 * would otherwise be cut or be undefined behaviour. */
static int values_fit(const mgr_message_binding *mb, const void *msg)
{
    for (int i = 0; i < mb->n_vars; i++) {
        const mgr_var_binding *v = &mb->vars[i];
        int ok = 1;
        if (v->var_type == CHASM_INT)
            (void)tp_double_to_i64(field_ref_get_double(&v->field, msg), &ok);
        else if (v->var_type == CHASM_STRING) {
            const char *s = field_ref_get_string(&v->field, msg);
            ok = !s || strlen(s) <= CHASM_STRING_MAX;
        }
        if (!ok)
            return 0;
    }
    return 1;
}

/* The message's own time of validity: plans compute message age from it.
 * A message type without utime is valid when it arrives; -1 when the stamp
 * is not representable (invalid). */
static int64_t input_stamp(const mgr_message_binding *mb, const void *msg, const tp_clock *clk)
{
    if (!mb->has_utime)
        return clk && clk->have ? clk->now : 0;
    int ok;
    int64_t utime = tp_double_to_i64(field_ref_get_double(&mb->utime, msg), &ok);
    return ok ? utime : -1;
}

/* Copy a decoded message's bound fields (or, for a messages variable, its
 * bytes as received) into the blackboard, once it has passed the time rule
 * and every value fits. */
static void apply_input(mgr_message_binding *mb, const void *msg, const void *raw, size_t len, int64_t utime)
{
    mgr_bindings *b = mb->owner;
    const tp_clock *clk = b->clock;
    tp_reason why = tp_input_offer(&mb->order, utime, clk && clk->have, clk ? clk->now : 0, b->future_tol_us);
    if (why != TP_OK) {
        tp_count(&b->time_drops, why, b->who ? b->who : "manager", mb->channel, utime);
        return;
    }
    if (mb->stream_var >= 0) {
        /* the whole message, as received: plugins decode it themselves */
        if (!raw || chasm_messages_append(b->machine, mb->stream_var, raw, len, utime) != 0) {
            if (b->range_drops++ == 0)
                fprintf(stderr, "%s: %s: dropped a %zu-byte message: over %d bytes, too large for the messages variable "
                                "'%s'; further drops of this kind are only counted\n",
                        b->who ? b->who : "manager", mb->channel, len, CHASM_MESSAGE_MAX_BYTES,
                        chasm_var_name(b->machine, mb->stream_var));
            return;
        }
        mb->messages_in++;
        b->inputs_applied++;
        return;
    }
    if (!values_fit(mb, msg)) {
        if (b->range_drops++ == 0)
            fprintf(stderr, "%s: %s: dropped a message with a value that does not fit its plan variable "
                            "(integer out of range or string over %d characters); further drops of this kind are only counted\n",
                    b->who ? b->who : "manager", mb->channel, CHASM_STRING_MAX);
        return;
    }
    for (int i = 0; i < mb->n_vars; i++) {
        const mgr_var_binding *v = &mb->vars[i];
        int ok;
        switch (v->var_type) {
        case CHASM_DOUBLE:
            chasm_var_set_double(b->machine, v->var, field_ref_get_double(&v->field, msg), utime);
            break;
        case CHASM_INT:
            chasm_var_set_int(b->machine, v->var, tp_double_to_i64(field_ref_get_double(&v->field, msg), &ok), utime);
            break;
        case CHASM_BOOL:
            chasm_var_set_bool(b->machine, v->var, field_ref_get_double(&v->field, msg) != 0.0, utime);
            break;
        case CHASM_STRING: {
            const char *s = field_ref_get_string(&v->field, msg);
            chasm_var_set_string(b->machine, v->var, s ? s : "", utime);
            break;
        }
        case CHASM_MESSAGES: break;   /* never a field: whole messages go above */
        }
    }
    b->inputs_applied++;
}

/* Lockstep only: a message of a step whose clock this manager has not heard
 * yet (mgr_held.h). A stamp beyond the future tolerance is not held: the time
 * rule drops it at once, as it would any time. */
static int arrived_before_its_clock(const mgr_bindings *b, int64_t utime)
{
    const tp_clock *clk = b->clock;
    return b->lockstep && *b->lockstep && clk && clk->have && tp_utime_valid(utime) && utime > clk->now &&
           utime <= tp_sat_add(clk->now, b->future_tol_us);
}

void mgr_input_received(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)recv_utime;
    mgr_message_binding *mb = user;
    mgr_bindings *b = mb->owner;
    int64_t utime = input_stamp(mb, msg, b->clock);
    size_t len = 0;
    const void *raw = rx_current_raw(mb->sub, &len);
    if (arrived_before_its_clock(b, utime) && raw && mgr_held_push(&b->held, mb, utime, raw, len) == 0) {
        if (b->held.held == 1)
            fprintf(stderr, "%s: %s: a message stamped %" PRId64 " us arrived before the clock of its step (now %" PRId64
                            " us): held for the cycle after that clock; further ones are only counted\n",
                    b->who ? b->who : "manager", channel, utime, b->clock->now);
        return;
    }
    apply_input(mb, msg, raw, len, utime);
}

static void apply_held(void *binding, int64_t utime, const void *data, size_t len, void *user)
{
    (void)user;
    mgr_message_binding *mb = binding;
    void *msg = calloc(1, mb->type->struct_size);
    /* it decoded once already, on arrival */
    if (msg && len <= INT32_MAX && rx_decode(mb->type, data, (int)len, msg) == 0) {
        apply_input(mb, msg, data, len, utime);
        mb->type->info()->decode_cleanup(msg);
    }
    free(msg);
}

void mgr_bindings_release_held(mgr_bindings *b)
{
    if (b->held.n && b->clock && b->clock->have)
        mgr_held_release(&b->held, b->clock->now, apply_held, NULL);
}

void mgr_bindings_recheck(mgr_bindings *b, int64_t now)
{
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (!mb->is_output && tp_input_recheck(&mb->order, now, b->future_tol_us))
            tp_count(&b->time_drops, TP_FUTURE, b->who ? b->who : "manager", mb->channel, mb->order.newest);
    }
}

int mgr_bindings_inputs_ready(const mgr_bindings *b)
{
    /* Delivered is not enough: a message dropped by the time rule or a range
     * check has not filled the blackboard. */
    for (int i = 0; i < b->n_msgs; i++)
        if (b->msgs[i].sub && !b->msgs[i].optional && !b->msgs[i].order.have && b->msgs[i].stream_var < 0)
            return 0;   /* a stream is events, not state: a plan never waits for its first message */
    return 1;
}

