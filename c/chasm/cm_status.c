/* Introspection: the active path, time in state and the last transition. */
#include "chasm/cm_machine.h"

void chasm_status_get(const chasm_machine *m, int64_t now, chasm_status *o)
{
    o->run_state = m->run;
    o->cycle = m->cycle;
    o->path_len = m->path_len;
    for (int d = 0; d < m->path_len; d++) {
        o->active_path[d] = m->path[d]->name;
        o->time_in_state_s[d] = (double)cm_span_us(now, m->path[d]->entered_us) * 1e-6;
    }
    o->leaf_path = m->path_len ? m->path[m->path_len - 1]->path : "";
    o->last_transition_us = m->last_us;
    o->last_from = m->last_from ? m->last_from->path : "";
    o->last_to = m->last_to ? m->last_to->path : "";
    o->last_condition = m->last_cond ? m->last_cond : "";
    o->n_tests = m->last_trans ? m->last_trans->n_refs : 0;
    for (int i = 0; i < o->n_tests; i++) {
        o->test_name[i] = m->last_trans->refs[i]->name;
        o->test_value[i] = m->last_vals[i];
    }
}
