/* The manager's life: created from the command line, plans loaded and
 * replaced while it runs, destroyed (manager.h). */
#include "managers/manager.h"

#include <stdio.h>
#include <string.h>

#include "managers/mgr_clock.h"
#include "managers/mgr_commands.h"
#include "managers/mgr_lcm.h"
#include "common/lcm_rx.h"

static void log_line(void *user, int64_t now_us, const char *state, const char *message)
{
    const manager_t *mg = user;
    fprintf(stderr, "%s %.3f %s: %s\n", mg->opt.name, (double)now_us / 1e6, state ? state : "", message);
}

static void plan_free(manager_t *mg, manager_plan *p)
{
    mgr_bindings_free(&p->bindings, mg->lcm);
    chasm_free(p->machine);
    p->machine = NULL;
}

int manager_load(manager_t *mg, const char *name, const char *text, manager_plan *out, mgr_errors *errs)
{
    chasm_errors *ce = NULL;
    out->machine = text ? chasm_load_string(name, text, strlen(text), &mg->chasm_opt, &ce)
                        : chasm_load_file(name, &mg->chasm_opt, &ce);
    if (!out->machine) {
        for (size_t i = 0; i < chasm_errors_count(ce); i++)
            mgr_errors_add(errs, "%s", chasm_errors_get(ce, i));
        chasm_errors_free(ce);
        return -1;
    }
    if (mgr_bindings_load(&out->bindings, mg->opt.bind_path, mg->opt.vehicle, out->machine, errs) != 0) {
        plan_free(mg, out);
        return -1;
    }
    /* Inputs are judged against the manager's clock (time rule). */
    out->bindings.clock = &mg->clock;
    out->bindings.lockstep = &mg->lockstep.lockstep;
    out->bindings.future_tol_us = mg->opt.future_tol_us;
    out->bindings.who = mg->opt.name;
    return 0;
}

int manager_replace_plan(manager_t *mg, manager_plan *p)
{
    plan_free(mg, &mg->plan);
    mg->plan = *p;
    memset(p, 0, sizeof *p);
    mg->started = 0;
    /* The bindings subscribe only now, in their final place: the handlers
     * keep a pointer to them. */
    return mgr_bindings_subscribe(&mg->plan.bindings, mg->lcm);
}

int manager_request_start(manager_t *mg)
{
    mg->waiting_for_start = 0;
    return mg->started;
}

void manager_request_stop(manager_t *mg) { mg->stop = 1; }

/* Plans load with the command line's plugin path and -D overrides, and log
 * through the manager. */
static void set_chasm_options(manager_t *mg)
{
    chasm_options *c = &mg->chasm_opt;
    c->plugin_path = mg->opt.plugin_path;
    c->n_plugin_path = mg->opt.n_plugin_path;
    c->param_names = mg->opt.param_names;
    c->param_values = mg->opt.param_values;
    c->n_params = mg->opt.n_params;
    c->future_tolerance_us = mg->opt.future_tol_us > 0 ? mg->opt.future_tol_us : 1; /* age backstop */
    c->log = log_line;
    c->log_user = mg;
}

/* The first plan failed: a bad -D is a usage error (2), like a bad option. */
static int load_failure_status(const mgr_errors *errs)
{
    for (size_t i = 0; i < errs->n; i++)
        if (!strncmp(errs->lines[i], "<-D ", 4))
            return 2;
    return 1;
}

int manager_create(manager_t *mg, const manager_options *opt)
{
    memset(mg, 0, sizeof *mg);
    mg->opt = *opt;
    mg->waiting_for_start = opt->wait_start;
    set_chasm_options(mg);
    if (mgr_auth_init(&mg->auth, mg->opt.key_file, mg->opt.name))
        return 2;
    mg->lcm = mgr_lcm_open(mg->opt.url, mg->opt.name, &mg->max_plan_bytes);
    if (!mg->lcm)
        return 2;
    tp_clock_init(&mg->clock, mg->opt.max_clock_jump_us);
    mgr_errors errs = {0};
    if (manager_load(mg, mg->opt.plan_path, NULL, &mg->plan, &errs) != 0) {
        int status = load_failure_status(&errs);
        mgr_errors_free(&errs);
        rx_lcm_destroy(mg->lcm);
        return status;
    }
    mgr_errors_free(&errs);
    mgr_status_init(&mg->status, mg->opt.vehicle, mg->opt.name, mg->opt.plan_path, mg->opt.status_rate_hz);
    mgr_structure_init(&mg->structure, mg->opt.vehicle, mg->opt.name);
    mgr_lockstep_init(&mg->lockstep, mg->opt.vehicle, mg->opt.name);
    if (mgr_bindings_subscribe(&mg->plan.bindings, mg->lcm) != 0 || mgr_commands_subscribe(mg) != 0 ||
        (mg->opt.sim_clock && mgr_clock_subscribe(mg) != 0)) {
        manager_destroy(mg);
        return 2;
    }
    return 0;
}

void manager_destroy(manager_t *mg)
{
    rx_unsubscribe(mg->lcm, mg->clock_sub);
    mgr_commands_unsubscribe(mg);
    plan_free(mg, &mg->plan);
    mgr_structure_free(&mg->structure);
    rx_lcm_destroy(mg->lcm);
    mgr_auth_clear(&mg->auth);
    mg->clock_sub = NULL;
    mg->lcm = NULL;
}
