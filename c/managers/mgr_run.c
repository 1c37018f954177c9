/* The manager's cycle loop (manager_run): wait for messages until a cycle is
 * due on the mission clock, start the plan once its inputs are ready, step
 * it, publish its outputs and its status. */
#include <stdio.h>
#include <time.h>

#include "managers/manager.h"
#include "managers/mgr_clock.h"
#include "managers/mgr_commands.h"

static double cpu_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec / 1e3;
}

static mgr_drop_counts drop_counts(const manager_t *mg)
{
    const tp_counts *in = &mg->plan.bindings.time_drops, *ck = &mg->clock_drops;
    mgr_drop_counts d = {
        .decode_errors = (int64_t)(mgr_bindings_decode_errors(&mg->plan.bindings) + mgr_commands_decode_errors(mg) +
                                   (mg->clock_sub ? rx_decode_errors(mg->clock_sub) : 0)),
        .dropped_invalid_time = (int64_t)in->n[TP_INVALID],
        .dropped_future = (int64_t)in->n[TP_FUTURE],
        .dropped_out_of_order = (int64_t)in->n[TP_OUT_OF_ORDER],
        .dropped_out_of_range = (int64_t)mg->plan.bindings.range_drops,
        .clock_invalid = (int64_t)ck->n[TP_INVALID],
        .clock_backwards = (int64_t)ck->n[TP_BACKWARDS],
        .clock_jumps = (int64_t)ck->n[TP_JUMP],
        .clock_old_term = (int64_t)ck->n[TP_OLD_TERM],
        .commands_refused = (int64_t)mg->commands_refused,
        .auth_unsigned = (int64_t)mg->auth.v.refused[AUTH_UNSIGNED],
        .auth_unknown_key = (int64_t)mg->auth.v.refused[AUTH_UNKNOWN_KEY],
        .auth_bad_mac = (int64_t)mg->auth.v.refused[AUTH_BAD_MAC],
        .auth_replay = (int64_t)mg->auth.v.refused[AUTH_REPLAY],
        .auth_stale = (int64_t)mg->auth.v.refused[AUTH_STALE],
    };
    mgr_stream_counts sc = mgr_bindings_stream_counts(&mg->plan.bindings);
    d.messages_in = (int64_t)sc.in;
    d.messages_out = (int64_t)sc.out;
    d.messages_missed = (int64_t)sc.missed;
    d.posts_refused = (int64_t)sc.refused;
    return d;
}

/* The structure goes out before the first status that names its plan_id:
 * rebuilt when the plan was loaded or replaced, then resent now and then. */
static void publish_status(manager_t *mg, double cost)
{
    if (mg->structure.built_for != mg->plan.machine)
        mgr_structure_build(&mg->structure, mg->plan.machine, mg->now_us);
    mgr_structure_update(&mg->structure, mg->lcm, mg->now_us);
    mg->status.plan_id = mg->structure.plan_id;
    mgr_drop_counts d = drop_counts(mg);
    mgr_status_update(&mg->status, mg->lcm, mg->plan.machine, mg->now_us, &d, cost);
}

/* Handles LCM messages (inputs, commands, the clock) for up to 20 ms, or on
 * the system clock until the next cycle is due. -1 when receiving failed. */
static int wait_for_messages(manager_t *mg, int64_t next_cycle)
{
    if (mg->opt.sim_clock)
        mgr_lockstep_poll(&mg->lockstep, mg->lcm);
    int64_t wait_ms = 20;
    if (!mg->opt.sim_clock) {
        mgr_clock_read_system(mg);
        if (mg->have_time && next_cycle > mg->now_us)
            wait_ms = (next_cycle - mg->now_us + 999) / 1000; /* round up: never spin */
        if (wait_ms > 1000)
            wait_ms = 1000;
    }
    /* A signal interrupts the wait: that is how a stop arrives. */
    if (rx_handle_timeout(mg->lcm, (int)(wait_ms > 0 ? wait_ms : 0)) < 0 && !mg->stop) {
        fprintf(stderr, "%s: LCM receive failed\n", mg->opt.name);
        return -1;
    }
    return 0;
}

/* 1 when a cycle runs now. Nothing runs before the clock, while --wait-start
 * holds, or (lockstep) on any message but the step's clock. A plan (the
 * first, and each LOAD_PLAN) starts once its required inputs have all
 * delivered; until then its status says LOADING, at the cycle rate. */
static int cycle_due(manager_t *mg, int64_t *next_cycle, int64_t period_us)
{
    if (!mg->opt.sim_clock)
        mgr_clock_read_system(mg);
    if (mg->have_time)
        mgr_bindings_recheck(&mg->plan.bindings, mg->now_us);
    if (!mg->have_time || mg->waiting_for_start || !mgr_lockstep_may_cycle(&mg->lockstep))
        return 0;
    if (!mg->started && !mgr_bindings_inputs_ready(&mg->plan.bindings)) {
        if (mg->now_us >= *next_cycle) { /* lcm-spy shows LOADING */
            publish_status(mg, 0);
            *next_cycle = tp_sat_add(mg->now_us, period_us);
        }
        return 0;
    }
    if (!mg->started) {
        chasm_start(mg->plan.machine, mg->now_us);
        mg->started = 1;
        *next_cycle = mg->now_us;
    }
    return mg->now_us >= *next_cycle;
}

/* One cycle: step, publish the outputs, then the status (when due) with the step's cost. */
static chasm_run_state cycle(manager_t *mg)
{
    double t0 = cpu_us();
    chasm_run_state rs = chasm_step(mg->plan.machine, mg->now_us);
    double cost = cpu_us() - t0;
    mgr_bindings_publish(&mg->plan.bindings, mg->lcm, mg->now_us);
    publish_status(mg, cost);
    return rs;
}

/* Leaves lockstep, says how it ended; the exit status. */
static int finish(manager_t *mg, chasm_run_state rs)
{
    if (mg->opt.sim_clock)
        mgr_lockstep_leave(&mg->lockstep, mg->lcm);
    fprintf(stderr, "%s: %s (%s)\n", mg->opt.name, mg->stop ? "stopped" : "plan ended", chasm_run_state_name(rs));
    const mgr_held *held = &mg->plan.bindings.held;
    if (held->held || held->overflow)
        fprintf(stderr, "%s: lockstep: %llu inputs arrived before their step's clock and waited for it, %llu applied "
                        "on arrival (over %d waiting)\n", mg->opt.name, (unsigned long long)held->held,
                (unsigned long long)held->overflow, MGR_HELD_MAX);
    mgr_stream_counts sc = mgr_bindings_stream_counts(&mg->plan.bindings);
    if (sc.n_streams)
        fprintf(stderr, "%s: messages: %llu in, %llu out, %llu missed, %llu posts refused\n", mg->opt.name,
                (unsigned long long)sc.in, (unsigned long long)sc.out, (unsigned long long)sc.missed,
                (unsigned long long)sc.refused);
    return rs == CHASM_RUN_ABORTED ? 3 : rs == CHASM_RUN_FAILED ? 4 : 0;
}

int manager_run(manager_t *mg)
{
    fprintf(stderr, "%s: running %s for %s at %.1f Hz on the %s clock\n", mg->opt.name, mg->opt.plan_path,
            mg->opt.vehicle, mg->opt.rate_hz, mg->opt.sim_clock ? "SIM.CLOCK" : "system");
    const int64_t period_us = (int64_t)(1e6 / mg->opt.rate_hz);
    int64_t next_cycle = 0;
    chasm_run_state rs = CHASM_RUN_LOADED;
    while (!mg->stop) {
        if (wait_for_messages(mg, next_cycle) != 0)
            return 2;
        if (mg->stop)
            break;
        /* Inputs that came ahead of their clock join the blackboard only
         * once the cycle of that clock is decided (mgr_held.h). */
        if (!cycle_due(mg, &next_cycle, period_us)) {
            mgr_bindings_release_held(&mg->plan.bindings);
            continue;
        }
        rs = cycle(mg);
        mgr_bindings_release_held(&mg->plan.bindings);
        /* Skip missed cycles instead of running a burst after a stall; the
         * clock is within 0..TP_UTIME_MAX, and the sums saturate anyway. */
        next_cycle = tp_sat_add(next_cycle, period_us);
        if (next_cycle <= mg->now_us)
            next_cycle = tp_sat_add(mg->now_us, period_us);
        if (mg->opt.exit_on_end && rs >= CHASM_RUN_DONE)
            break;
    }
    return finish(mg, rs);
}
