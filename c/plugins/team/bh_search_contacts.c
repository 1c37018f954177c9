/* search_contacts: the search vehicle's contact list. Each sidescan contact
 * (a messages input of sidescan_contact_t) is merged into the own list
 * (tm_contacts.h); a contact whose merged score reaches min_score is
 * mine-like: CONTACT_NEW, and it is queued for the link, which repeats it
 * until the RI vehicle acknowledges it. A contact that fails to decode is
 * counted and dropped. */
#include <stdio.h>

#include "auv/auv_sidescan_contact_t.h"
#include "tm_behaviors.h"
#include "tm_store.h"

const chasm_param_spec tm_search_params[SC_NPARAMS] = {
    [SC_RX] = CHASM_READ("rx", CHASM_MESSAGES, "", "contacts",
                         "sidescan contacts (a `messages` variable bound to <V>.CONTACTS)"),
    [SC_MIN_SCORE] = CHASM_PARAM_DOUBLE_RANGE("min_score", "", 0.5, 0, 1,
                                              "a merged contact at least this mine-like is reported"),
    [SC_MERGE] = CHASM_PARAM_DOUBLE_RANGE("merge", "m", 5, 0, 100, "looks within this distance are one object"),
};
_Static_assert(CHASM_COUNT(tm_search_params) == SC_NPARAMS, "search_contacts schema and slots disagree");

int tm_search_start(chasm_ctx *c, void *state)
{
    (void)state;
    return tm_store_for(c, "search_contacts") ? 0 : -1;
}

chasm_status_code tm_search_step(chasm_ctx *c, void *state)
{
    (void)state;
    tm_store *s = tm_store_get();
    const void *msg;
    size_t len;
    double min_score = chasm_param_double(c, SC_MIN_SCORE);
    while ((msg = chasm_next_message(c, SC_RX, &len))) {
        auv_sidescan_contact_t k;
        if (len > 1u << 20 || auv_sidescan_contact_t_decode(msg, 0, (int)len, &k) < 0) {
            s->undecodable++;
            continue;
        }
        int created;
        int i = tm_contacts_add(&s->contacts, k.north_m, k.east_m, k.position_sigma_m, k.confidence,
                                (double)k.utime * 1e-6, chasm_param_double(c, SC_MERGE), &created);
        auv_sidescan_contact_t_decode_cleanup(&k);
        if (i < 0)
            continue;
        tm_contact *m = &s->contacts.c[i];
        if (!m->queued && m->score >= min_score) {
            m->queued = 1;
            tm_outbox_contact(&s->out, m->number);
            char text[64];
            snprintf(text, sizeof text, "score %.2f after %d looks", m->score, m->looks);
            tm_post(s, c->now_us, TM_EV_CONTACT_NEW, s->me, m->number, m->n, m->e, 0, text);
        }
    }
    return CHASM_RUNNING;
}
