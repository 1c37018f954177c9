/* The project's rule for message timestamps (docs/channels.md, "Time and
 * timestamps"), shared by the managers and auv-nav; the Python side
 * (python/auvlcm) implements the same numbers.
 *
 *  - A utime is valid when 0 <= utime <= TP_UTIME_MAX (2100-01-01 in Unix
 *    time). An invalid stamp is counted and dropped.
 *  - A clock never runs backwards; a forward jump of more than
 *    TP_MAX_CLOCK_JUMP_US is refused until a second clock message confirms it.
 *  - A data message more than TP_FUTURE_TOLERANCE_US ahead of the receiver's
 *    clock is "from the future"; one older than the newest accepted on the
 *    same input is "out of order"; both are counted and dropped.
 *  - Time arithmetic saturates: no signed overflow from any stamp. */
#ifndef AUV_TIME_POLICY_H
#define AUV_TIME_POLICY_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TP_UTIME_MAX INT64_C(4102444800000000)      /* 2100-01-01T00:00:00Z [us] */
#define TP_MAX_CLOCK_JUMP_US INT64_C(60000000)      /* 60 s of global time */
#define TP_FUTURE_TOLERANCE_US INT64_C(1000000)     /* 1 s */

/* Why a message was dropped; TP_OK when it was accepted. */
typedef enum {
    TP_OK = 0,
    TP_INVALID,         /* utime outside 0..TP_UTIME_MAX */
    TP_FUTURE,          /* more than the tolerance ahead of the receiver's clock */
    TP_OUT_OF_ORDER,    /* older than the newest accepted value of the same input */
    TP_BACKWARDS,       /* a clock value older than the current one */
    TP_JUMP,            /* a clock jump larger than the maximum, not (yet) confirmed */
    TP_OLD_TERM,        /* a clock from an election term older than one already accepted */
    TP_N_REASONS
} tp_reason;

const char *tp_reason_name(tp_reason r);

static inline int tp_utime_valid(int64_t t) { return t >= 0 && t <= TP_UTIME_MAX; }

/* a + b and a - b, saturated to [INT64_MIN, INT64_MAX]. */
int64_t tp_sat_add(int64_t a, int64_t b);
int64_t tp_sat_sub(int64_t a, int64_t b);

/* A double (as decoded from a message field) to int64 without undefined
 * behaviour: 0 and *ok = 0 when it is NaN or outside int64's range. */
int64_t tp_double_to_i64(double v, int *ok);

/* A receiver's notion of global time (SIM.CLOCK or any clock message). */
typedef struct {
    int64_t now;            /* latest accepted value */
    int have;               /* a value was accepted */
    int64_t jump_to;        /* a refused jump waiting for confirmation */
    int jump_pending;
    int64_t max_jump_us;    /* TP_MAX_CLOCK_JUMP_US unless configured */
} tp_clock;

void tp_clock_init(tp_clock *c, int64_t max_jump_us);
/* Offer a clock value: TP_OK when accepted (c->now updated), or why not. */
tp_reason tp_clock_offer(tp_clock *c, int64_t utime);

/* The election term a world's clock comes from (sim_clock_t.term). A server
 * frozen past the failover timeout can resume and send a clock of its old
 * term after another node has taken over: a clock from a term older than one
 * already accepted is refused, whatever its time. Check the term first, offer
 * the clock value, and accept the term only when the value was accepted. */
typedef struct {
    int32_t term;
    int have;
} tp_term;

static inline tp_reason tp_term_check(const tp_term *t, int32_t term)
{
    return t->have && term < t->term ? TP_OLD_TERM : TP_OK;
}

static inline void tp_term_accept(tp_term *t, int32_t term)
{
    if (!t->have || term > t->term) {
        t->term = term;
        t->have = 1;
    }
}

/* One input (a channel, a sensor): the newest accepted stamp. */
typedef struct {
    int64_t newest;
    int have;
} tp_input;

/* Judge a data message's stamp against the receiver's clock (have_now = 0:
 * no clock yet, only validity and order are checked). TP_OK: accepted and
 * in->newest updated. */
tp_reason tp_input_offer(tp_input *in, int64_t stamp, int have_now, int64_t now, int64_t future_tol_us);
/* Judge what was held before a clock existed: 1 (and the input is reset,
 * so newer messages are accepted again) when its newest stamp is from the
 * future of `now`. */
int tp_input_recheck(tp_input *in, int64_t now, int64_t future_tol_us);

/* Counters per reason, with one log line the first time each reason occurs. */
typedef struct {
    uint64_t n[TP_N_REASONS];
} tp_counts;

/* Count a drop; prints "<who>: <what>: dropped ... (<reason>); further drops
 * of this kind are only counted" to stderr the first time. */
void tp_count(tp_counts *c, tp_reason r, const char *who, const char *what, int64_t stamp);

#ifdef __cplusplus
}
#endif
#endif
