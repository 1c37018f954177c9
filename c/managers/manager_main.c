/* chasm-manager: run one CHASM mission plan as a manager process.
 *
 *   chasm-manager --plan navigator.chasm --bind vehicle.bind --vehicle AUV1 --name NAVIGATOR
 *                 [--rate 10] [--clock sim|system] [--lcm-url URL] [--exit-on-end] [--wait-start]
 *                 [--plugin-path DIR]... [--plugin-dir DIR --allowlist FILE] [-D name=value]...
 *
 * Each cycle (rate_hz on the mission clock): chasm_step(), then the plan's
 * outputs are published and its status goes to <VEHICLE>.CHASM.<NAME>. With
 * --clock sim the mission clock is SIM.CLOCK (nothing runs until it ticks);
 * with --clock system it is the host's clock. SIGINT/SIGTERM end the process
 * after the current cycle. A plan starts once every input channel it binds
 * has delivered a message, except inputs bound `optional` (until then its
 * status says LOADING). Exit status: 0 done or stopped, 1 load error,
 * 3 aborted, 4 failed (with --exit-on-end). */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "auv/auv_sim_clock_t.h"
#include "managers/manager.h"
#include "managers/mgr_lcm.h"

static manager_t *g_mg;

static void on_signal(int sig)
{
    (void)sig;
    if (g_mg)
        g_mg->stop = 1;
}

static void log_line(void *user, int64_t now_us, const char *state, const char *message)
{
    manager_t *mg = user;
    fprintf(stderr, "%s %.3f %s: %s\n", mg->opt.name, (double)now_us / 1e6, state ? state : "", message);
}

chasm_machine *manager_load(manager_t *mg, const char *name, const char *text, mgr_bindings *out_b, mgr_errors *out)
{
    chasm_errors *errs = NULL;
    chasm_machine *m = text ? chasm_load_string(name, text, strlen(text), &mg->chasm_opt, &errs)
                            : chasm_load_file(name, &mg->chasm_opt, &errs);
    if (!m) {
        for (size_t i = 0; i < chasm_errors_count(errs); i++)
            mgr_errors_add(out, "%s", chasm_errors_get(errs, i));
        chasm_errors_free(errs);
        return NULL;
    }
    if (mgr_bindings_load(out_b, mg->opt.bind_path, mg->opt.vehicle, m, out) != 0) {
        mgr_bindings_free(out_b, mg->lcm);
        chasm_free(m);
        return NULL;
    }
    /* Inputs are judged against the manager's clock (time rule). */
    out_b->clock = &mg->clock;
    out_b->future_tol_us = mg->opt.future_tol_us;
    out_b->who = mg->opt.name;
    return m;
}

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

static int64_t system_now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static double cpu_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec / 1e3;
}

static mgr_drop_counts drop_counts(const manager_t *mg)
{
    const tp_counts *in = &mg->b.time_drops, *ck = &mg->clock_drops;
    mgr_drop_counts d = {
        .decode_errors = (int64_t)(mgr_bindings_decode_errors(&mg->b) + mgr_commands_decode_errors(mg) +
                                   (mg->clock_sub ? rx_decode_errors(mg->clock_sub) : 0)),
        .dropped_invalid_time = (int64_t)in->n[TP_INVALID],
        .dropped_future = (int64_t)in->n[TP_FUTURE],
        .dropped_out_of_order = (int64_t)in->n[TP_OUT_OF_ORDER],
        .dropped_out_of_range = (int64_t)mg->b.range_drops,
        .clock_invalid = (int64_t)ck->n[TP_INVALID],
        .clock_backwards = (int64_t)ck->n[TP_BACKWARDS],
        .clock_jumps = (int64_t)ck->n[TP_JUMP],
        .clock_old_term = (int64_t)ck->n[TP_OLD_TERM],
        .commands_refused = (int64_t)mg->commands_refused,
    };
    mgr_stream_counts sc = mgr_bindings_stream_counts(&mg->b);
    d.messages_in = (int64_t)sc.in;
    d.messages_out = (int64_t)sc.out;
    d.messages_missed = (int64_t)sc.missed;
    d.posts_refused = (int64_t)sc.refused;
    return d;
}

static void publish_status(manager_t *mg, double cost)
{
    mgr_drop_counts d = drop_counts(mg);
    mgr_status_publish(&mg->status, mg->lcm, mg->m, mg->now_us, &d, cost);
}

static int run(manager_t *mg)
{
    const int64_t period_us = (int64_t)(1e6 / mg->opt.rate_hz);
    int64_t next_cycle = 0;
    chasm_run_state rs = CHASM_RUN_LOADED;
    while (!mg->stop) {
        if (mg->opt.sim_clock)
            mgr_lockstep_poll(&mg->lockstep, mg->lcm);
        int64_t wait_ms = 20;
        if (!mg->opt.sim_clock) {
            clock_reading(mg, system_now_us(), "system clock");
            if (mg->have_time && next_cycle > mg->now_us)
                wait_ms = (next_cycle - mg->now_us + 999) / 1000; /* round up: never spin */
            if (wait_ms > 1000)
                wait_ms = 1000;
        }
        /* A signal interrupts the wait: that is how a stop arrives. */
        if (lcm_handle_timeout(mg->lcm, (int)(wait_ms > 0 ? wait_ms : 0)) < 0 && !mg->stop) {
            fprintf(stderr, "%s: LCM receive failed\n", mg->opt.name);
            return 2;
        }
        if (mg->stop)
            break;
        if (!mg->opt.sim_clock)
            clock_reading(mg, system_now_us(), "system clock");
        if (mg->have_time)
            mgr_bindings_recheck(&mg->b, mg->now_us);
        if (!mg->have_time || mg->opt.wait_start || !mgr_lockstep_may_cycle(&mg->lockstep))
            continue;
        if (!mg->started && !mgr_bindings_inputs_ready(&mg->b)) {
            if (mg->now_us >= next_cycle) { /* say so at the cycle rate: lcm-spy shows LOADING */
                publish_status(mg, 0);
                next_cycle = tp_sat_add(mg->now_us, period_us);
            }
            continue;
        }
        if (!mg->started) {
            chasm_start(mg->m, mg->now_us);
            mg->started = 1;
            next_cycle = mg->now_us;
        }
        if (mg->now_us < next_cycle)
            continue;
        double t0 = cpu_us();
        rs = chasm_step(mg->m, mg->now_us);
        double cost = cpu_us() - t0;
        mgr_bindings_publish(&mg->b, mg->lcm, mg->now_us);
        publish_status(mg, cost);
        /* Skip missed cycles instead of running a burst after a stall; the
         * clock is within 0..TP_UTIME_MAX, and the sums saturate anyway. */
        next_cycle = tp_sat_add(next_cycle, period_us);
        if (next_cycle <= mg->now_us)
            next_cycle = tp_sat_add(mg->now_us, period_us);
        if (mg->opt.exit_on_end && rs >= CHASM_RUN_DONE)
            break;
    }
    if (mg->opt.sim_clock)
        mgr_lockstep_leave(&mg->lockstep, mg->lcm);
    fprintf(stderr, "%s: %s (%s)\n", mg->opt.name, mg->stop ? "stopped" : "plan ended", chasm_run_state_name(rs));
    mgr_stream_counts sc = mgr_bindings_stream_counts(&mg->b);
    if (sc.n_streams)
        fprintf(stderr, "%s: messages: %llu in, %llu out, %llu missed, %llu posts refused\n", mg->opt.name,
                (unsigned long long)sc.in, (unsigned long long)sc.out, (unsigned long long)sc.missed,
                (unsigned long long)sc.refused);
    return rs == CHASM_RUN_ABORTED ? 3 : rs == CHASM_RUN_FAILED ? 4 : 0;
}

int main(int argc, char **argv)
{
    static manager_t mg;
    int pa = manager_parse_args(&mg.opt, argc, argv);
    if (pa != 0)
        return pa > 0 ? 0 : 2;
    mg.chasm_opt.plugin_path = mg.opt.plugin_path;
    mg.chasm_opt.n_plugin_path = mg.opt.n_plugin_path;
    mg.chasm_opt.param_names = mg.opt.param_names;
    mg.chasm_opt.param_values = mg.opt.param_values;
    mg.chasm_opt.n_params = mg.opt.n_params;
    mg.chasm_opt.future_tolerance_us = mg.opt.future_tol_us > 0 ? mg.opt.future_tol_us : 1; /* age backstop */
    mg.chasm_opt.log = log_line;
    mg.chasm_opt.log_user = &mg;
    mg.lcm = mgr_lcm_open(mg.opt.url, mg.opt.name, &mg.max_plan_bytes);
    if (!mg.lcm)
        return 2;
    tp_clock_init(&mg.clock, mg.opt.max_clock_jump_us);
    mgr_errors errs = {0};
    mg.m = manager_load(&mg, mg.opt.plan_path, NULL, &mg.b, &errs);
    if (!mg.m) {
        /* a bad -D is a usage error (2), like a bad option */
        int usage_error = 0;
        for (size_t i = 0; i < errs.n; i++)
            usage_error |= !strncmp(errs.lines[i], "<-D ", 4);
        mgr_errors_free(&errs);
        lcm_destroy(mg.lcm);
        return usage_error ? 2 : 1;
    }
    mgr_errors_free(&errs);
    mgr_status_init(&mg.status, mg.opt.vehicle, mg.opt.name, mg.opt.plan_path);
    mgr_lockstep_init(&mg.lockstep, mg.opt.vehicle, mg.opt.name);
    int rc = 2;
    if (mgr_bindings_subscribe(&mg.b, mg.lcm) == 0 && mgr_commands_subscribe(&mg) == 0 &&
        (!mg.opt.sim_clock ||
         (mg.clock_sub = rx_subscribe(mg.lcm, "SIM.CLOCK", auv_type_find("sim_clock_t"), on_clock, &mg)))) {
        g_mg = &mg;
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigaction(SIGINT, &sa, NULL);
        sigaction(SIGTERM, &sa, NULL);
        fprintf(stderr, "%s: running %s for %s at %.1f Hz on the %s clock\n", mg.opt.name, mg.opt.plan_path,
                mg.opt.vehicle, mg.opt.rate_hz, mg.opt.sim_clock ? "SIM.CLOCK" : "system");
        rc = run(&mg);
    }
    rx_unsubscribe(mg.lcm, mg.clock_sub);
    mgr_commands_unsubscribe(&mg);
    mgr_bindings_free(&mg.b, mg.lcm);
    chasm_free(mg.m);
    lcm_destroy(mg.lcm);
    return rc;
}
