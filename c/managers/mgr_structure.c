/* The running plan's structure as auv.chasm_structure_t (mgr_structure.h):
 * built once per plan from libchasm's introspection (chasm_structure.h),
 * digested into a plan_id that every status repeats, sent on its own channel. */
#include "managers/mgr_structure.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chasm/chasm_structure.h"

static const char *const TYPES[] = {"double", "int", "bool", "string", "messages"};

void mgr_structure_init(mgr_structure *s, const char *vehicle, const char *manager)
{
    memset(s, 0, sizeof *s);
    s->vehicle = vehicle;
    s->manager = manager;
    snprintf(s->channel, sizeof s->channel, "%s.PLAN.%s", vehicle, manager);
}

static void free_tables(mgr_structure *s)
{
    auv_chasm_structure_t *m = &s->msg;
    void *tables[] = {m->state_name, m->state_path, m->state_parent, m->state_default_child, m->state_next,
                      m->state_next_done, m->state_loc, m->action_state, m->action_text, m->action_time_model,
                      m->action_loc, m->trans_from, m->trans_to, m->trans_history, m->trans_condition,
                      m->trans_first_test, m->trans_n_tests, m->trans_loc, m->trans_test_name, m->var_name,
                      m->var_kind, m->var_type, m->var_unit, m->param_name, m->param_value};
    for (size_t i = 0; i < sizeof tables / sizeof tables[0]; i++)
        free(tables[i]);
    for (size_t i = 0; i < s->n_owned; i++)
        free(s->owned[i]);
    free(s->owned);
    s->owned = NULL;
    s->n_owned = s->cap_owned = 0;
    memset(m, 0, sizeof *m);
}

void mgr_structure_free(mgr_structure *s)
{
    free_tables(s);
    s->built_for = NULL;
}

/* A string formatted here, freed with the tables; NULL out of memory. */
__attribute__((format(printf, 2, 3))) static char *own(mgr_structure *s, const char *fmt, ...)
{
    if (s->n_owned == s->cap_owned) {
        size_t cap = s->cap_owned ? 2 * s->cap_owned : 64;
        char **o = realloc(s->owned, cap * sizeof *o);
        if (!o) return NULL;
        s->owned = o;
        s->cap_owned = cap;
    }
    va_list ap, again;
    va_start(ap, fmt);
    va_copy(again, ap);
    int len = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *out = len >= 0 ? malloc((size_t)len + 1) : NULL;
    if (out) vsnprintf(out, (size_t)len + 1, fmt, again);
    va_end(again);
    if (out) s->owned[s->n_owned++] = out;
    return out;
}

static char *where(mgr_structure *s, chasm_where w) { return own(s, "%s:%d:%d", w.file, w.line, w.col); }

#define ALLOC(field, n) ((m->field = calloc((size_t)(n) ? (size_t)(n) : 1, sizeof *m->field)) != NULL)

static int states(mgr_structure *s, const chasm_machine *cm, int *n_actions, int *n_trans)
{
    auv_chasm_structure_t *m = &s->msg;
    int n = (int)chasm_state_count(cm);
    m->n_states = n;
    m->initial_state = chasm_initial_state(cm);
    if (!ALLOC(state_name, n) || !ALLOC(state_path, n) || !ALLOC(state_parent, n) || !ALLOC(state_default_child, n) ||
        !ALLOC(state_next, n) || !ALLOC(state_next_done, n) || !ALLOC(state_loc, n))
        return -1;
    *n_actions = 0;
    *n_trans = chasm_abort_count(cm);
    for (int i = 0; i < n; i++) {
        chasm_state_info st;
        chasm_state_info_get(cm, i, &st);
        m->state_name[i] = (char *)st.name;
        m->state_path[i] = (char *)st.path;
        m->state_parent[i] = st.parent;
        m->state_default_child[i] = st.default_child;
        m->state_next[i] = st.next;
        m->state_next_done[i] = st.next_done;
        if (!(m->state_loc[i] = where(s, st.where))) return -1;
        *n_actions += st.n_actions;
        *n_trans += st.n_transitions;
    }
    return 0;
}

static int actions(mgr_structure *s, const chasm_machine *cm, int n)
{
    auv_chasm_structure_t *m = &s->msg;
    m->n_actions = n;
    if (!ALLOC(action_state, n) || !ALLOC(action_text, n) || !ALLOC(action_time_model, n) || !ALLOC(action_loc, n))
        return -1;
    int a = 0;
    for (int i = 0; i < m->n_states; i++) {
        chasm_state_info st;
        chasm_state_info_get(cm, i, &st);
        for (int k = 0; k < st.n_actions; k++, a++) {
            chasm_action_info ai;
            chasm_action_info_get(cm, i, k, &ai);
            m->action_state[a] = i;
            m->action_text[a] = (char *)ai.text;
            m->action_time_model[a] = strcmp(ai.time_model, "every") && strcmp(ai.time_model, "after")
                                          ? (char *)ai.time_model
                                          : own(s, "%s %g s", ai.time_model, ai.period_s);
            m->action_loc[a] = where(s, ai.where);
            if (!m->action_time_model[a] || !m->action_loc[a]) return -1;
        }
    }
    return 0;
}

static int add_trans(mgr_structure *s, const chasm_trans_info *t, int k, int *n_refs, int cap_refs)
{
    auv_chasm_structure_t *m = &s->msg;
    m->trans_from[k] = t->from;
    m->trans_to[k] = t->to;
    m->trans_history[k] = (int8_t)t->history;
    m->trans_condition[k] = (char *)t->condition;
    m->trans_first_test[k] = *n_refs;
    m->trans_n_tests[k] = (int16_t)t->n_tests;
    if (!(m->trans_loc[k] = where(s, t->where))) return -1;
    for (int r = 0; r < t->n_tests; r++) {
        if (*n_refs == cap_refs) return -1;
        m->trans_test_name[(*n_refs)++] = (char *)t->test_name[r];
    }
    return 0;
}

static int transitions(mgr_structure *s, const chasm_machine *cm, int n)
{
    auv_chasm_structure_t *m = &s->msg;
    m->n_transitions = n;
    if (!ALLOC(trans_from, n) || !ALLOC(trans_to, n) || !ALLOC(trans_history, n) || !ALLOC(trans_condition, n) ||
        !ALLOC(trans_first_test, n) || !ALLOC(trans_n_tests, n) || !ALLOC(trans_loc, n))
        return -1;
    /* the tests named in all conditions, counted first */
    chasm_trans_info t;
    int cap_refs = 0, n_refs = 0, k = 0;
    for (int j = 0; j < chasm_abort_count(cm); j++)
        cap_refs += chasm_trans_info_get(cm, -1, j, &t) ? 0 : t.n_tests;
    for (int i = 0; i < m->n_states; i++) {
        chasm_state_info st;
        chasm_state_info_get(cm, i, &st);
        for (int j = 0; j < st.n_transitions; j++)
            cap_refs += chasm_trans_info_get(cm, i, j, &t) ? 0 : t.n_tests;
    }
    if (!ALLOC(trans_test_name, cap_refs)) return -1;
    for (int j = 0; j < chasm_abort_count(cm); j++, k++)
        if (chasm_trans_info_get(cm, -1, j, &t) || add_trans(s, &t, k, &n_refs, cap_refs)) return -1;
    for (int i = 0; i < m->n_states; i++) {
        chasm_state_info st;
        chasm_state_info_get(cm, i, &st);
        for (int j = 0; j < st.n_transitions; j++, k++)
            if (chasm_trans_info_get(cm, i, j, &t) || add_trans(s, &t, k, &n_refs, cap_refs)) return -1;
    }
    m->n_trans_tests = n_refs;
    return 0;
}

static int vars_and_params(mgr_structure *s, const chasm_machine *cm)
{
    auv_chasm_structure_t *m = &s->msg;
    int n = (int)chasm_var_count(cm);
    m->n_vars = n;
    if (!ALLOC(var_name, n) || !ALLOC(var_kind, n) || !ALLOC(var_type, n) || !ALLOC(var_unit, n)) return -1;
    for (int i = 0; i < n; i++) {
        chasm_type ty = chasm_var_type(cm, i);
        m->var_name[i] = (char *)chasm_var_name(cm, i);
        m->var_kind[i] = (int8_t)chasm_var_kind_of(cm, i);
        m->var_type[i] = (char *)((unsigned)ty < 5 ? TYPES[ty] : "?");
        m->var_unit[i] = (char *)chasm_var_unit(cm, i);
    }
    int np = (int)chasm_param_count(cm);
    m->n_params = np;
    if (!ALLOC(param_name, np) || !ALLOC(param_value, np)) return -1;
    for (int i = 0; i < np; i++) {
        char buf[CHASM_STRING_MAX + 8];
        const char *name = chasm_param_get(cm, (size_t)i, buf, sizeof buf);
        m->param_name[i] = (char *)(name ? name : "");
        if (!(m->param_value[i] = own(s, "%s", buf))) return -1;
    }
    return 0;
}

/* FNV-1a 64 of the message as encoded with its times and id blank: two
 * managers running one plan agree, and any change of the plan changes it. */
static int digest(mgr_structure *s)
{
    auv_chasm_structure_t *m = &s->msg;
    int64_t u = m->utime, l = m->loaded_utime;
    m->utime = m->loaded_utime = 0;
    m->plan_id = "";
    int len = auv_chasm_structure_t_encoded_size(m);
    unsigned char *buf = malloc((size_t)len);
    if (!buf) return -1;
    auv_chasm_structure_t_encode(buf, 0, len, m);
    uint64_t h = 1469598103934665603ULL;
    for (int i = 0; i < len; i++)
        h = (h ^ buf[i]) * 1099511628211ULL;
    free(buf);
    snprintf(s->plan_id, sizeof s->plan_id, "%016llx", (unsigned long long)h);
    m->plan_id = s->plan_id;
    m->utime = u;
    m->loaded_utime = l;
    return 0;
}

/* Too big to send: the header alone, saying so. */
static void cut_to_header(mgr_structure *s, int bytes)
{
    auv_chasm_structure_t keep = s->msg;
    int states = keep.n_states;
    auv_chasm_structure_t *m = &s->msg;
    m->n_states = m->n_actions = m->n_transitions = m->n_trans_tests = m->n_vars = m->n_params = 0;
    m->initial_state = -1;
    m->truncated = 1;
    m->note = own(s, "%d states encode to %d bytes, over the %d a structure may have", states, bytes,
                  MGR_MAX_STRUCTURE_BYTES);
    if (!m->note) m->note = "too big";
}

int mgr_structure_build(mgr_structure *s, const chasm_machine *cm, int64_t now_us)
{
    free_tables(s);
    s->built_for = cm;
    s->published = 0;
    auv_chasm_structure_t *m = &s->msg;
    m->vehicle = (char *)s->vehicle;
    m->manager = (char *)s->manager;
    const char *name = chasm_plan_name(cm), *slash = strrchr(name, '/');
    m->plan = (char *)(slash ? slash + 1 : name);
    m->note = "";
    m->plan_id = "";
    m->loaded_utime = now_us;
    int n_actions = 0, n_trans = 0;
    if (states(s, cm, &n_actions, &n_trans) || actions(s, cm, n_actions) || transitions(s, cm, n_trans) ||
        vars_and_params(s, cm)) {
        free_tables(s);
        s->built_for = cm;
        s->plan_id[0] = 0;
        return -1;
    }
    int bytes = auv_chasm_structure_t_encoded_size(m);
    if (bytes > MGR_MAX_STRUCTURE_BYTES) cut_to_header(s, bytes);
    return digest(s);
}

int mgr_structure_update(mgr_structure *s, lcm_t *lcm, int64_t now_us)
{
    if (!s->built_for || !s->plan_id[0]) return 0;
    int due = !s->published || now_us - s->last_us >= MGR_STRUCTURE_PERIOD_US || now_us < s->last_us;
    if (!due) return 0;
    s->msg.utime = now_us;
    auv_chasm_structure_t_publish(lcm, s->channel, &s->msg);
    s->published = 1;
    s->last_us = now_us;
    return 1;
}
