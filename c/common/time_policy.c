#include "common/time_policy.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>

const char *tp_reason_name(tp_reason r)
{
    static const char *n[TP_N_REASONS] = {"ok", "invalid time", "from the future", "out of order",
                                           "clock backwards", "unconfirmed clock jump",
                                           "clock from an older term"};
    return (unsigned)r < TP_N_REASONS ? n[r] : "?";
}

int64_t tp_sat_add(int64_t a, int64_t b)
{
    int64_t r;
    if (__builtin_add_overflow(a, b, &r))
        return b > 0 ? INT64_MAX : INT64_MIN;
    return r;
}

int64_t tp_sat_sub(int64_t a, int64_t b)
{
    int64_t r;
    if (__builtin_sub_overflow(a, b, &r))
        return b < 0 ? INT64_MAX : INT64_MIN;
    return r;
}

int64_t tp_double_to_i64(double v, int *ok)
{
    /* 2^63 is exactly representable; every double below it fits. */
    if (!(v >= -9223372036854775808.0 && v < 9223372036854775808.0)) {
        *ok = 0;
        return 0;
    }
    *ok = 1;
    return (int64_t)v;
}

void tp_clock_init(tp_clock *c, int64_t max_jump_us)
{
    c->now = 0;
    c->have = 0;
    c->jump_to = 0;
    c->jump_pending = 0;
    c->max_jump_us = max_jump_us > 0 ? max_jump_us : TP_MAX_CLOCK_JUMP_US;
}

tp_reason tp_clock_offer(tp_clock *c, int64_t t)
{
    if (!tp_utime_valid(t))
        return TP_INVALID;
    if (!c->have) {
        c->now = t;
        c->have = 1;
        return TP_OK;
    }
    if (t < c->now)
        return TP_BACKWARDS;
    if (t - c->now > c->max_jump_us) { /* both valid: no overflow */
        if (c->jump_pending && t >= c->jump_to && t - c->jump_to <= c->max_jump_us) {
            c->now = t; /* a second message consistent with the jump: it was real */
            c->jump_pending = 0;
            return TP_OK;
        }
        c->jump_to = t;
        c->jump_pending = 1;
        return TP_JUMP;
    }
    c->now = t;
    c->jump_pending = 0;
    return TP_OK;
}

tp_reason tp_input_offer(tp_input *in, int64_t stamp, int have_now, int64_t now, int64_t tol)
{
    if (!tp_utime_valid(stamp))
        return TP_INVALID;
    if (have_now && stamp > tp_sat_add(now, tol))
        return TP_FUTURE;
    if (in->have && stamp < in->newest)
        return TP_OUT_OF_ORDER;
    in->newest = stamp;
    in->have = 1;
    return TP_OK;
}

int tp_input_recheck(tp_input *in, int64_t now, int64_t tol)
{
    if (!in->have || in->newest <= tp_sat_add(now, tol))
        return 0;
    in->have = 0;
    in->newest = 0;
    return 1;
}

void tp_count(tp_counts *c, tp_reason r, const char *who, const char *what, int64_t stamp)
{
    if ((unsigned)r >= TP_N_REASONS || r == TP_OK)
        return;
    if (c->n[r]++ == 0)
        fprintf(stderr, "%s: %s: dropped a message stamped %" PRId64 " us (%s); further drops of this kind are only counted\n",
                who, what, stamp, tp_reason_name(r));
}
