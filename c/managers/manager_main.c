/* chasm-manager: run one CHASM mission plan as a manager process.
 *
 *   chasm-manager --plan navigator.chasm --bind vehicle.bind --vehicle AUV1 --name NAVIGATOR
 *                 [--rate 10] [--clock sim|system] [--url URL] [--exit-on-end] [--wait-start]
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

static manager_t *g_mg;

static void on_signal(int sig)
{
    (void)sig;
    if (g_mg)
        g_mg->stop = 1;
}

static void usage(void)
{
    fprintf(stderr, "usage: chasm-manager --plan FILE --bind FILE --vehicle ID --name NAME [--rate HZ]\n"
                    "       [--clock sim|system] [--url URL] [--exit-on-end] [--wait-start]\n"
                    "       [--plugin-path DIR]... [--plugin-dir DIR --allowlist FILE] [-D name=value]...\n");
}

int manager_parse_args(manager_options *o, int argc, char **argv)
{
    memset(o, 0, sizeof *o);
    o->rate_hz = 10.0;
    o->sim_clock = 1;
    o->url = "udpm://239.255.76.67:7667?ttl=0";
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        if (!strcmp(a, "--plan") && v) o->plan_path = v;
        else if (!strcmp(a, "--bind") && v) o->bind_path = v;
        else if (!strcmp(a, "--vehicle") && v) o->vehicle = v;
        else if (!strcmp(a, "--name") && v) o->name = v;
        else if (!strcmp(a, "--url") && v) o->url = v;
        else if (!strcmp(a, "--rate") && v) o->rate_hz = atof(v);
        else if (!strcmp(a, "--clock") && v && (!strcmp(v, "sim") || !strcmp(v, "system"))) o->sim_clock = !strcmp(v, "sim");
        else if (!strcmp(a, "--plugin-dir") && v) o->plugin_dir = v;
        else if (!strcmp(a, "--allowlist") && v) o->allowlist = v;
        else if (!strcmp(a, "--plugin-path") && v && o->n_plugin_path < 15) o->plugin_path[o->n_plugin_path++] = v;
        else if (!strcmp(a, "-D") && v && strchr(v, '=') && o->n_params < 64) {
            /* -D name=value: split in place (argv is ours). */
            char *eq = strchr(argv[i + 1], '=');
            *eq = '\0';
            o->param_names[o->n_params] = argv[i + 1];
            o->param_values[o->n_params++] = eq + 1;
        } else {
            takes = 0;
            if (!strcmp(a, "--exit-on-end")) o->exit_on_end = 1;
            else if (!strcmp(a, "--wait-start")) o->wait_start = 1;
            else {
                fprintf(stderr, "chasm-manager: bad or incomplete option '%s'\n", a);
                return -1;
            }
        }
        i += takes;
    }
    if (!o->plan_path || !o->bind_path || !o->vehicle || !o->name || !(o->rate_hz > 0)) {
        usage();
        return -1;
    }
    if (o->plugin_dir && o->n_plugin_path < 16) {
        /* Uploaded plugins take precedence over installed ones. */
        memmove(o->plugin_path + 1, o->plugin_path, o->n_plugin_path * sizeof o->plugin_path[0]);
        o->plugin_path[0] = o->plugin_dir;
        o->n_plugin_path++;
    }
    return 0;
}

static void log_line(void *user, int64_t now_us, const char *state, const char *message)
{
    manager_t *mg = user;
    fprintf(stderr, "%s %.3f %s: %s\n", mg->opt.name, (double)now_us / 1e6, state ? state : "", message);
}

chasm_machine *manager_load(manager_t *mg, const char *name, const char *text, mgr_bindings *out_b)
{
    chasm_errors *errs = NULL;
    chasm_machine *m = text ? chasm_load_string(name, text, strlen(text), &mg->chasm_opt, &errs)
                            : chasm_load_file(name, &mg->chasm_opt, &errs);
    if (!m) {
        for (size_t i = 0; i < chasm_errors_count(errs); i++)
            fprintf(stderr, "%s\n", chasm_errors_get(errs, i));
        chasm_errors_free(errs);
        return NULL;
    }
    if (mgr_bindings_load(out_b, mg->opt.bind_path, mg->opt.vehicle, m) != 0) {
        mgr_bindings_free(out_b, mg->lcm);
        chasm_free(m);
        return NULL;
    }
    return m;
}

static void on_clock(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)channel;
    (void)recv_utime;
    manager_t *mg = user;
    const auv_sim_clock_t *c = msg;
    /* Global time never runs backwards for the plan, whatever the network does. */
    if (!mg->have_time || c->utime > mg->now_us)
        mg->now_us = c->utime;
    mg->have_time = 1;
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

static int64_t decode_errors(const manager_t *mg)
{
    return (int64_t)(mgr_bindings_decode_errors(&mg->b) + mgr_commands_decode_errors(mg));
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
            mg->now_us = system_now_us();
            mg->have_time = 1;
            if (next_cycle > mg->now_us)
                wait_ms = (next_cycle - mg->now_us + 999) / 1000; /* round up: never spin */
        }
        /* A signal interrupts the wait: that is how a stop arrives. */
        if (lcm_handle_timeout(mg->lcm, (int)(wait_ms > 0 ? wait_ms : 0)) < 0 && !mg->stop) {
            fprintf(stderr, "%s: LCM receive failed\n", mg->opt.name);
            return 2;
        }
        if (mg->stop)
            break;
        if (!mg->opt.sim_clock)
            mg->now_us = system_now_us();
        if (!mg->have_time || mg->opt.wait_start || !mgr_lockstep_may_cycle(&mg->lockstep))
            continue;
        if (!mg->started && !mgr_bindings_inputs_ready(&mg->b)) {
            if (mg->now_us >= next_cycle) { /* say so at the cycle rate: lcm-spy shows LOADING */
                mgr_status_publish(&mg->status, mg->lcm, mg->m, mg->now_us, decode_errors(mg), 0);
                next_cycle = mg->now_us + period_us;
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
        mgr_status_publish(&mg->status, mg->lcm, mg->m, mg->now_us, decode_errors(mg), cost);
        /* Skip missed cycles instead of running a burst after a stall. */
        next_cycle += period_us;
        if (next_cycle <= mg->now_us)
            next_cycle = mg->now_us + period_us;
        if (mg->opt.exit_on_end && rs >= CHASM_RUN_DONE)
            break;
    }
    if (mg->opt.sim_clock)
        mgr_lockstep_leave(&mg->lockstep, mg->lcm);
    fprintf(stderr, "%s: %s (%s)\n", mg->opt.name, mg->stop ? "stopped" : "plan ended", chasm_run_state_name(rs));
    return rs == CHASM_RUN_ABORTED ? 3 : rs == CHASM_RUN_FAILED ? 4 : 0;
}

int main(int argc, char **argv)
{
    static manager_t mg;
    if (manager_parse_args(&mg.opt, argc, argv) != 0)
        return 2;
    mg.chasm_opt.plugin_path = mg.opt.plugin_path;
    mg.chasm_opt.n_plugin_path = mg.opt.n_plugin_path;
    mg.chasm_opt.param_names = mg.opt.param_names;
    mg.chasm_opt.param_values = mg.opt.param_values;
    mg.chasm_opt.n_params = mg.opt.n_params;
    mg.chasm_opt.log = log_line;
    mg.chasm_opt.log_user = &mg;
    mg.lcm = lcm_create(mg.opt.url);
    if (!mg.lcm) {
        fprintf(stderr, "chasm-manager: cannot open LCM at %s (no multicast route? see README)\n", mg.opt.url);
        return 2;
    }
    mg.m = manager_load(&mg, mg.opt.plan_path, NULL, &mg.b);
    if (!mg.m) {
        lcm_destroy(mg.lcm);
        return 1;
    }
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
