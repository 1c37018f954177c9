#include "managers/mgr_status.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "auv/auv_chasm_status_t.h"
#include "chasm/chasm_structure.h"

/* Counters are 64-bit here and 32-bit on the wire: saturate, never wrap. */
static int32_t clamp32(int64_t v) { return v > INT32_MAX ? INT32_MAX : v < 0 ? 0 : (int32_t)v; }

void mgr_status_init(mgr_status_ctx *s, const char *vehicle, const char *manager, const char *plan, double rate_hz)
{
    memset(s, 0, sizeof *s);
    s->period_us = rate_hz > 0 ? (int64_t)(1e6 / rate_hz) : 0;
    s->vehicle = vehicle;
    s->manager = manager;
    const char *slash = strrchr(plan, '/');
    s->plan = slash ? slash + 1 : plan;
    snprintf(s->channel, sizeof s->channel, "%s.CHASM.%s", vehicle, manager);
}

void mgr_status_set_plan(mgr_status_ctx *s, const char *plan)
{
    const char *slash = strrchr(plan, '/');
    snprintf(s->plan_buf, sizeof s->plan_buf, "%s", slash ? slash + 1 : plan);
    s->plan = s->plan_buf;
}

static void publish(const mgr_status_ctx *s, lcm_t *lcm, const chasm_machine *m, const chasm_status *st, int64_t now_us,
                    const mgr_drop_counts *drops, double cycle_cost_us)
{
    auv_chasm_status_t msg;
    memset(&msg, 0, sizeof msg);
    msg.utime = now_us;
    msg.vehicle = (char *)s->vehicle;
    msg.manager = (char *)s->manager;
    msg.plan = (char *)s->plan;
    msg.run_state = (int8_t)st->run_state;
    msg.cycle = st->cycle;
    msg.path_len = (int16_t)st->path_len;
    msg.active_path = (char **)st->active_path;
    msg.time_in_state_s = (double *)st->time_in_state_s;
    msg.last_transition_utime = st->last_transition_us;
    msg.last_from = (char *)(st->last_from ? st->last_from : "");
    msg.last_to = (char *)(st->last_to ? st->last_to : "");
    msg.last_condition = (char *)(st->last_condition ? st->last_condition : "");
    msg.n_tests = (int16_t)st->n_tests;
    msg.test_name = (char **)st->test_name;
    int8_t values[CHASM_STATUS_MAX_TESTS];
    for (int i = 0; i < st->n_tests; i++)
        values[i] = st->test_value[i];
    msg.test_value = values;
    msg.decode_errors = clamp32(drops->decode_errors);
    msg.dropped_invalid_time = clamp32(drops->dropped_invalid_time);
    msg.dropped_future = clamp32(drops->dropped_future);
    msg.dropped_out_of_order = clamp32(drops->dropped_out_of_order);
    msg.dropped_out_of_range = clamp32(drops->dropped_out_of_range);
    msg.clock_invalid = clamp32(drops->clock_invalid);
    msg.clock_backwards = clamp32(drops->clock_backwards);
    msg.clock_jumps = clamp32(drops->clock_jumps);
    msg.clock_old_term = clamp32(drops->clock_old_term);
    msg.commands_refused = clamp32(drops->commands_refused);
    msg.auth_unsigned = clamp32(drops->auth_unsigned);
    msg.auth_unknown_key = clamp32(drops->auth_unknown_key);
    msg.auth_bad_mac = clamp32(drops->auth_bad_mac);
    msg.auth_replay = clamp32(drops->auth_replay);
    msg.auth_stale = clamp32(drops->auth_stale);
    msg.messages_in = clamp32(drops->messages_in);
    msg.messages_out = clamp32(drops->messages_out);
    msg.messages_missed = clamp32(drops->messages_missed);
    msg.posts_refused = clamp32(drops->posts_refused);
    msg.cycle_cost_us = cycle_cost_us;
    msg.plan_id = (char *)(s->plan_id ? s->plan_id : "");
    int8_t live[MGR_STATUS_MAX_LIVE_TESTS];
    bool live_b[MGR_STATUS_MAX_LIVE_TESTS];
    int n_live = chasm_live_tests(m, live_b, MGR_STATUS_MAX_LIVE_TESTS);
    msg.live_tests_cut = n_live > MGR_STATUS_MAX_LIVE_TESTS;
    msg.n_live_tests = (int16_t)(msg.live_tests_cut ? MGR_STATUS_MAX_LIVE_TESTS : n_live);
    for (int i = 0; i < msg.n_live_tests; i++)
        live[i] = live_b[i];
    msg.live_test_value = live;
    double var_values[MGR_STATUS_MAX_VAR_VALUES];
    int n_vars = (int)chasm_var_count(m);
    msg.n_var_values = (int16_t)(n_vars < MGR_STATUS_MAX_VAR_VALUES ? n_vars : MGR_STATUS_MAX_VAR_VALUES);
    for (int i = 0; i < msg.n_var_values; i++)
        var_values[i] = chasm_var_number(m, i);
    msg.var_value = var_values;
    auv_chasm_status_t_publish(lcm, s->channel, &msg);
}

/* Whether a count of something dropped or refused moved (the flow counts,
 * messages in and out, move every cycle and say nothing new). */
static int faults_changed(const mgr_drop_counts *a, const mgr_drop_counts *b)
{
    mgr_drop_counts x = *a, y = *b;
    x.messages_in = y.messages_in = 0;
    x.messages_out = y.messages_out = 0;
    return memcmp(&x, &y, sizeof x) != 0;
}

/* Whether what an operator acts on differs from the last status; remembers it. */
static int changed(mgr_status_ctx *s, const chasm_status *st, const mgr_drop_counts *drops)
{
    const char *leaf = st->leaf_path ? st->leaf_path : "";
    int diff = !s->published || s->run_state != (int)st->run_state ||
               s->last_transition_us != st->last_transition_us || s->path_len != st->path_len ||
               strncmp(s->leaf, leaf, sizeof s->leaf - 1) != 0 || faults_changed(&s->drops, drops);
    s->run_state = (int)st->run_state;
    s->last_transition_us = st->last_transition_us;
    s->path_len = st->path_len;
    snprintf(s->leaf, sizeof s->leaf, "%s", leaf);
    s->drops = *drops;
    return diff;
}

int mgr_status_update(mgr_status_ctx *s, lcm_t *lcm, const chasm_machine *m, int64_t now_us,
                      const mgr_drop_counts *drops, double cycle_cost_us)
{
    if (cycle_cost_us > s->max_cost_us)
        s->max_cost_us = cycle_cost_us;
    chasm_status st;
    chasm_status_get(m, now_us, &st);
    int due = changed(s, &st, drops) || s->period_us <= 0 || now_us - s->last_us >= s->period_us ||
              now_us < s->last_us; /* a clock that went back (a new world): start over */
    if (!due)
        return 0;
    publish(s, lcm, m, &st, now_us, drops, s->max_cost_us);
    s->published = 1;
    s->last_us = now_us;
    s->max_cost_us = 0;
    return 1;
}
