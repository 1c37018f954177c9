#include "drivers/common/drv_clock.h"

#include <time.h>

#include "auv/auv_sim_clock_t.h"

static void on_clock(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)channel;
    (void)recv_utime;
    drv_clock *c = user;
    const auv_sim_clock_t *m = msg;
    if (tp_term_check(&c->term, m->term) != TP_OK || tp_clock_offer(&c->sim, m->utime) != TP_OK) {
        c->refused++;
        return;
    }
    tp_term_accept(&c->term, m->term);
}

int drv_clock_init(drv_clock *c, drv_clock_mode mode, lcm_t *lcm)
{
    c->mode = mode;
    c->refused = 0;
    tp_clock_init(&c->sim, TP_MAX_CLOCK_JUMP_US);
    c->term.have = 0;
    c->term.term = 0;
    c->sub = NULL;
    if (mode != DRV_CLOCK_SIM)
        return 0;
    const auv_type_entry_t *t = auv_type_find("sim_clock_t");
    c->sub = t ? rx_subscribe(lcm, "SIM.CLOCK", t, on_clock, c) : NULL;
    return c->sub ? 0 : -1;
}

void drv_clock_close(drv_clock *c, lcm_t *lcm)
{
    if (c->sub)
        rx_unsubscribe(lcm, c->sub);
    c->sub = NULL;
}

int64_t drv_clock_now(const drv_clock *c)
{
    if (c->mode == DRV_CLOCK_SIM)
        return c->sim.have ? c->sim.now : -1;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

int64_t drv_monotonic_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}
