#include "tm_tdma.h"

#include <math.h>

void tm_tdma_init(tm_tdma *t, double slot_s, int slots, int my_slot, double window_s)
{
    t->slot_us = llround(slot_s * 1e6);
    if (t->slot_us < 1)
        t->slot_us = 1;
    t->slots = slots > 0 ? slots : 1;
    t->my_slot = my_slot;
    t->window_us = llround(window_s * 1e6);
    if (t->window_us > t->slot_us)
        t->window_us = t->slot_us;
    t->last_round = -1;
}

/* floor division (times before the clock's zero stay consistent) */
static int64_t floordiv(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

int tm_tdma_slot(const tm_tdma *t, int64_t now_us)
{
    int64_t k = floordiv(now_us, t->slot_us);
    int64_t s = k % t->slots;
    return (int)(s < 0 ? s + t->slots : s);
}

int64_t tm_tdma_may_send(const tm_tdma *t, int64_t now_us)
{
    int64_t round_us = t->slot_us * t->slots;
    int64_t round = floordiv(now_us, round_us);
    int64_t into = now_us - round * round_us - (int64_t)t->my_slot * t->slot_us;
    if (into < 0 || into >= t->window_us || round == t->last_round)
        return -1;
    return round;
}

void tm_tdma_sent(tm_tdma *t, int64_t round) { t->last_round = round; }
