/* The manager's mission clock (mgr_clock.h): a reading becomes the manager's
 * now_us only when the time rule accepts it. */
#include "managers/mgr_clock.h"

#include <time.h>

#include "auv/auv_sim_clock_t.h"

/* Offer a clock reading to the time rule; 1 when accepted. */
static int clock_reading(manager_t *mg, int64_t utime, const char *source)
{
    tp_reason why = tp_clock_offer(&mg->clock, utime);
    if (why != TP_OK) {
        tp_count(&mg->clock_drops, why, mg->opt.name, source, utime);
        return 0;
    }
    mg->now_us = mg->clock.now;
    mg->have_time = 1;
    return 1;
}

static void on_clock(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)channel;
    (void)recv_utime;
    manager_t *mg = user;
    const auv_sim_clock_t *c = msg;
    /* Global time never runs backwards for the plan and never leaps on one
     * message, whatever the network does (time rule, docs/channels.md). */
    tp_reason old = tp_term_check(&mg->clock_term, c->term);
    if (old != TP_OK) {     /* a server that resumed after a freeze, in its old term */
        tp_count(&mg->clock_drops, old, mg->opt.name, "SIM.CLOCK", c->utime);
        return;
    }
    if (!clock_reading(mg, c->utime, "SIM.CLOCK"))
        return;
    tp_term_accept(&mg->clock_term, c->term);
    mgr_lockstep_on_clock(&mg->lockstep, mg->lcm, c);
}

int mgr_clock_subscribe(manager_t *mg)
{
    mg->clock_sub = rx_subscribe(mg->lcm, "SIM.CLOCK", auv_type_find("sim_clock_t"), on_clock, mg);
    return mg->clock_sub ? 0 : -1;
}

void mgr_clock_read_system(manager_t *mg)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    clock_reading(mg, (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000, "system clock");
}
