#include "managers/mgr_lockstep.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "auv/auv_lockstep_t.h"

static int64_t mono_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static void send(mgr_lockstep *ls, lcm_t *lcm, int8_t kind, int64_t step, int64_t utime)
{
    auv_lockstep_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.participant = ls->name;
    m.kind = kind;
    m.step = step;
    auv_lockstep_t_publish(lcm, "SIM.LOCKSTEP", &m);
}

void mgr_lockstep_init(mgr_lockstep *ls, const char *vehicle, const char *name)
{
    memset(ls, 0, sizeof *ls);
    snprintf(ls->name, sizeof ls->name, "%s.%s", vehicle, name);
    ls->pending_step = -1;
    ls->last_done = -1;
    ls->last_done_utime = INT64_MIN;
}

void mgr_lockstep_on_clock(mgr_lockstep *ls, lcm_t *lcm, const auv_sim_clock_t *c)
{
    ls->seen_clock = 1;
    ls->lockstep = c->mode == AUV_SIM_CLOCK_T_MODE_LOCKSTEP;
    if (!ls->lockstep)
        return;
    /* A step already done (a repeated clock message) is acknowledged again.
     * Drivers that leave `step` at 0 still advance utime: either counts. */
    if (c->step <= ls->last_done && c->utime <= ls->last_done_utime) {
        send(ls, lcm, AUV_LOCKSTEP_T_KIND_STEP_DONE, c->step, c->utime);
        ls->next_resend_ms = mono_ms() + MGR_LOCKSTEP_RESEND_MS;
        return;
    }
    ls->pending_step = c->step;
    ls->pending_utime = c->utime;
}

int mgr_lockstep_may_cycle(const mgr_lockstep *ls)
{
    return !ls->lockstep || ls->pending_step >= 0;
}

void mgr_lockstep_poll(mgr_lockstep *ls, lcm_t *lcm)
{
    if (!ls->seen_clock) {
        int64_t now = mono_ms();
        if (now >= ls->next_register_ms) {
            ls->next_register_ms = now + 1000;
            send(ls, lcm, AUV_LOCKSTEP_T_KIND_REGISTER, 0, 0);
        }
        return;
    }
    if (ls->pending_step >= 0) {
        send(ls, lcm, AUV_LOCKSTEP_T_KIND_STEP_DONE, ls->pending_step, ls->pending_utime);
        ls->last_done = ls->pending_step;
        ls->last_done_utime = ls->pending_utime;
        ls->pending_step = -1;
        ls->next_resend_ms = mono_ms() + MGR_LOCKSTEP_RESEND_MS;
        return;
    }
    /* No newer clock came: the report (or the next clock) may have been lost.
     * Repeat it; the server counts a step once and republishes a clock that
     * this repeat shows was missed. */
    if (ls->lockstep && ls->last_done >= 0) {
        int64_t now = mono_ms();
        if (now >= ls->next_resend_ms) {
            ls->next_resend_ms = now + MGR_LOCKSTEP_RESEND_MS;
            ls->resent++;
            send(ls, lcm, AUV_LOCKSTEP_T_KIND_STEP_DONE, ls->last_done, ls->last_done_utime);
        }
    }
}

void mgr_lockstep_leave(mgr_lockstep *ls, lcm_t *lcm)
{
    if (ls->seen_clock || ls->next_register_ms)
        send(ls, lcm, AUV_LOCKSTEP_T_KIND_LEAVE, ls->last_done, 0);
}
