#include "tm_store.h"

#include <stdio.h>
#include <string.h>

static tm_store the_store;

tm_store *tm_store_get(void) { return &the_store; }

static int same_roster(const tm_roster *a, const tm_roster *b)
{
    if (a->n != b->n)
        return 0;
    for (int i = 0; i < a->n; i++)
        if (strcmp(a->name[i], b->name[i]))
            return 0;
    return 1;
}

void tm_store_configure(tm_store *s, const tm_roster *r, int me, int64_t now_us, int repeat)
{
    if (s->configured && same_roster(&s->roster, r) && s->me == me && now_us >= s->last_now_us) {
        s->out.repeat = repeat > 0 ? repeat : 1;
        return;
    }
    memset(s, 0, sizeof *s);
    s->configured = 1;
    s->roster = *r;
    s->me = me;
    s->last_now_us = now_us;
    s->t_start = (double)now_us * 1e-6;
    tm_outbox_init(&s->out, repeat);
    s->state = TM_ST_TRANSIT;
    s->merge_m = 5.0;
}

tm_store *tm_store_for(chasm_ctx *c, const char *behavior)
{
    tm_store *s = tm_store_get();
    if (!s->configured || (double)c->now_us < (double)s->last_now_us) {
        char msg[200];
        snprintf(msg, sizeof msg,
                 "%s: team_link is not running: put team_link(team = ..., me = ...) in this state "
                 "or an enclosing one, before this action", behavior);
        chasm_log(c, msg);
        return NULL;
    }
    return s;
}

void tm_post(tm_store *s, int64_t now_us, int kind, int origin, int number, double n, double e, int result,
              const char *text)
{
    if (s->n_events >= TM_MAX_EVENTS) {
        s->events_dropped++;
        return;
    }
    tm_event *v = &s->events[s->n_events++];
    *v = (tm_event){now_us, kind, origin, number, n, e, result, ""};
    if (text)
        snprintf(v->text, sizeof v->text, "%s", text);
}

const char *tm_name(const tm_store *s, int index)
{
    return index >= 0 && index < s->roster.n ? s->roster.name[index] : "";
}
