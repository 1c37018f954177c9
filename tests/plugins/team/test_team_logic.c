/* The team plugin's pure logic (no engine, no codec): contact merging, the
 * RI target queue, the route planner, the takeover rule, TDMA timing, the
 * priority frame filling with its ack/repeat bookkeeping, and the closest
 * point of approach used by keep_clear. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "../common/plugin_test.h"
#include "team_tests.h"
#include "plugins/team/tm_contacts.h"
#include "plugins/team/tm_front_rule.h"
#include "plugins/team/tm_keepclear.h"
#include "plugins/team/tm_lines.h"
#include "plugins/team/tm_outbox.h"
#include "plugins/team/tm_route.h"
#include "plugins/team/tm_targets.h"
#include "plugins/team/tm_tdma.h"

/* a small deterministic generator (the tests must not depend on libc's rand) */
static uint64_t rng = 88172645463325252ull;
static double uniform(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

void contacts_merge_repeated_looks(void)
{
    static tm_contact_list l;
    memset(&l, 0, sizeof l);
    int created;
    CHECK(tm_contacts_add(&l, 100, 50, 2, 0.8, 10, 5, &created) == 0 && created == 1);
    /* a second look 3 m away, same sigma: merged to the midpoint, sigma / sqrt 2 */
    CHECK(tm_contacts_add(&l, 103, 50, 2, 0.4, 20, 5, &created) == 0 && created == 0);
    CHECK_NEAR(l.c[0].n, 101.5, 1e-9);
    CHECK_NEAR(l.c[0].sigma, 2 / sqrt(2.0), 1e-9);
    CHECK_NEAR(l.c[0].score, 0.6, 1e-9);
    CHECK(l.c[0].looks == 2 && l.c[0].t_first == 10 && l.c[0].t_last == 20);
    /* 6 m from the merged estimate: another object */
    CHECK(tm_contacts_add(&l, 107.6, 50, 2, 0.9, 30, 5, &created) == 1 && created == 1);
    /* a look between the two goes to the nearer one */
    CHECK(tm_contacts_add(&l, 105.0, 50, 2, 0.9, 40, 5, &created) == 1 && created == 0);
    /* a precise look dominates an imprecise one; sigma 0 is floored, not a division by zero */
    CHECK(tm_contacts_add(&l, 300, 300, 10, 0.5, 50, 5, &created) == 2);
    CHECK(tm_contacts_add(&l, 302, 300, 0, 0.5, 51, 5, &created) == 2);
    CHECK(l.c[2].n > 301.99 && isfinite(l.c[2].sigma) && l.c[2].sigma <= 0.1);
    /* a full list counts and refuses */
    for (int i = l.n; i < TM_MAX_CONTACTS; i++)
        tm_contacts_add(&l, 1000 + 20 * i, 0, 1, 0.5, 60, 5, &created);
    CHECK(l.n == TM_MAX_CONTACTS);
    CHECK(tm_contacts_add(&l, -1000, -1000, 1, 0.5, 70, 5, &created) == -1 && l.full == 1);
}

void targets_merge_across_reporters(void)
{
    static tm_target_queue q;
    memset(&q, 0, sizeof q);
    int created;
    CHECK(tm_targets_report(&q, (tm_key){0, 3}, 100, 100, 2, 0.7, 5, 5, &created) == 0 && created);
    /* the repeat of the same report: same target, not merged twice */
    CHECK(tm_targets_report(&q, (tm_key){0, 3}, 100, 100, 2, 0.7, 6, 5, &created) == 0 && !created);
    CHECK_NEAR(q.t[0].sigma, 2, 1e-9);
    /* vehicle 1 reports the same object 3 m off: an alias, position merged */
    CHECK(tm_targets_report(&q, (tm_key){1, 0}, 103, 100, 2, 0.9, 7, 5, &created) == 0 && !created);
    CHECK(q.t[0].n_alias == 1 && q.t[0].alias[0].origin == 1 && q.t[0].alias[0].number == 0);
    CHECK_NEAR(q.t[0].n, 101.5, 1e-9);
    CHECK_NEAR(q.t[0].score, 0.9, 1e-9);
    /* its repeat is recognised by name even though it is 3 m from the merged point */
    CHECK(tm_targets_report(&q, (tm_key){1, 0}, 103, 100, 2, 0.9, 8, 5, &created) == 0 && !created);
    CHECK(q.t[0].n_alias == 1);
    /* a distinct object */
    CHECK(tm_targets_report(&q, (tm_key){2, 0}, 200, 100, 2, 0.6, 9, 5, &created) == 1 && created);
    int idx[8];
    CHECK(tm_targets_pending(&q, idx, 8) == 2);
    /* looks: far from both: nothing; near target 1 with a near-certain
     * sensor: one look decides it */
    CHECK(tm_targets_look(&q, 150, 100, TM_RESULT_MINE, 0.9, 5, 5, 1e-3) == -1);
    CHECK(tm_targets_look(&q, 201, 99, TM_RESULT_NOT_MINE, 0.99999, 5, 5, 1e-3) == 1);
    CHECK(q.t[1].state == TM_T_IDENTIFIED && q.t[1].result == TM_RESULT_NOT_MINE);
    CHECK(tm_targets_look(&q, 201, 99, TM_RESULT_MINE, 0.99999, 5, 5, 1e-3) == -1);   /* decided ones take no more */
    /* looks that carry nothing (coin-flip, below, not a number) do not count */
    CHECK(tm_targets_look(&q, 101, 100, TM_RESULT_MINE, 0.5, 5, 5, 1e-3) == -1);
    CHECK(tm_targets_look(&q, 101, 100, TM_RESULT_MINE, 0.2, 5, 5, 1e-3) == -1);
    CHECK(tm_targets_look(&q, 101, 100, TM_RESULT_MINE, NAN, 5, 5, 1e-3) == -1);
    CHECK(tm_targets_look(&q, 101, 100, 7, 0.9, 5, 5, 1e-3) == -1);
    CHECK(q.t[0].looks == 0);
    /* a 0.9 sensor to 1e-3: log(999) / log(9) = 3.14, so four more "mine"
     * than "not mine". A wrong look among right ones delays the call: M N M M
     * M is +3, not enough; the sixth look, M, makes +4 and decides mine. */
    int seq[6] = {TM_RESULT_MINE, TM_RESULT_NOT_MINE, TM_RESULT_MINE, TM_RESULT_MINE, TM_RESULT_MINE, TM_RESULT_MINE};
    for (int k = 0; k < 5; k++)
        CHECK(tm_targets_look(&q, 101, 100, seq[k], 0.9, 5, 5, 1e-3) == -2);
    CHECK(tm_targets_look(&q, 101, 100, seq[5], 0.9, 5, 5, 1e-3) == 0 && q.t[0].result == TM_RESULT_MINE);
    CHECK(q.t[0].looks == 6);
    CHECK(tm_targets_pending(&q, idx, 8) == 0);
    /* the gate: a first look is another vehicle's frame (10 m here); later
     * ones gather around the looks so far (5 m), so a neighbour 7 m from them
     * is not taken for the object */
    q = (tm_target_queue){0};
    tm_targets_report(&q, (tm_key){0, 1}, 0, 0, 1, 0.9, 0, 5, &created);
    CHECK(tm_targets_look(&q, 11, 0, TM_RESULT_MINE, 0.9, 10, 5, 1e-3) == -1);
    CHECK(tm_targets_look(&q, 8, 0, TM_RESULT_MINE, 0.9, 10, 5, 1e-3) == -2);
    double wn, we;
    tm_target_where(&q.t[0], &wn, &we);
    CHECK_NEAR(wn, 8, 1e-12);
    CHECK(tm_targets_look(&q, 1, 0, TM_RESULT_NOT_MINE, 0.9, 10, 5, 1e-3) == -1);
    CHECK(tm_targets_look(&q, 10, 0, TM_RESULT_MINE, 0.9, 10, 5, 1e-3) == -2);
    tm_target_where(&q.t[0], &wn, &we);
    CHECK_NEAR(wn, 9, 1e-12);
    CHECK(q.t[0].looks == 2);
}

/* The sequential test keeps its promise: 20 000 targets, each looked at by a
 * sensor right 90 % of the time until decided. To ident_error 0.05 the calls
 * are wrong in at most 5 % (Wald: 1 / (1 + 9^2) = 1.2 % here), against the
 * 10 % a single look would give; to 1e-3, in at most 0.1 %. */
static uint64_t xs_state = 88172645463325252ull;
static double uniform01(void)
{
    xs_state ^= xs_state << 13;
    xs_state ^= xs_state >> 7;
    xs_state ^= xs_state << 17;
    return (double)(xs_state >> 11) * 0x1.0p-53;
}

static double wrong_calls(double max_error, double *mean_looks)
{
    static tm_target_queue q;
    int wrong = 0, trials = 20000;
    long looks = 0;
    for (int k = 0; k < trials; k++) {
        int created, mine = k % 2, truth = mine ? TM_RESULT_MINE : TM_RESULT_NOT_MINE;
        q = (tm_target_queue){0};
        tm_targets_report(&q, (tm_key){0, 1}, 0, 0, 1, 0.9, 0, 5, &created);
        int r = -2;
        for (int i = 0; i < 500 && r == -2; i++) {
            int right = uniform01() < 0.9;
            int said = right == mine ? TM_RESULT_MINE : TM_RESULT_NOT_MINE;
            r = tm_targets_look(&q, 0.5, 0, said, 0.9, 5, 5, max_error);
            looks++;
        }
        CHECK(r == 0);
        wrong += q.t[0].result != truth;
    }
    *mean_looks = (double)looks / trials;
    return (double)wrong / trials;
}

void ident_error_bounds_wrong_calls(void)
{
    double looks_05, looks_001;
    double e05 = wrong_calls(0.05, &looks_05), e001 = wrong_calls(1e-3, &looks_001);
    CHECK(e05 > 0.005 && e05 < 0.05);    /* two net looks: about 1.2 % */
    CHECK(e001 < 1e-3);                  /* four net looks: about 0.015 % */
    /* the price is looks: more of them for the stricter bound */
    CHECK(looks_05 > 2 && looks_001 > looks_05 + 1.5);
}

/* On a line: targets at +1, -2, +4, -8 from the start. Nearest-neighbour
 * zig-zags (1 + 3 + 6 + 12 = 22 m); the best open path goes to +4 first and
 * then sweeps to -8 (4 + 12 = 16 m). */
void route_beats_nearest_neighbour(void)
{
    gd_point s = {0, 0};
    gd_point p[4] = {{1, 0}, {-2, 0}, {4, 0}, {-8, 0}};
    int nn[4], r[4];
    tm_route_nearest(s, p, 4, nn);
    tm_route_plan(s, p, 4, r);
    CHECK_NEAR(tm_route_length(s, p, nn, 4), 22, 1e-9);
    CHECK_NEAR(tm_route_length(s, p, r, 4), 16, 1e-9);
    /* each target exactly once */
    int seen = 0;
    for (int i = 0; i < 4; i++)
        seen |= 1 << r[i];
    CHECK(seen == 15);
    /* over random queues: never worse than nearest-neighbour by more than a
     * little, and clearly better on average */
    double sum_nn = 0, sum_r = 0;
    int worse = 0;
    for (int k = 0; k < 40; k++) {
        gd_point q[30];
        int n = 5 + k % 25, o1[30], o2[30];
        for (int i = 0; i < n; i++)
            q[i] = (gd_point){uniform() * 1000 - 500, uniform() * 1000 - 500};
        tm_route_nearest(s, q, n, o1);
        tm_route_plan(s, q, n, o2);
        double a = tm_route_length(s, q, o1, n), b = tm_route_length(s, q, o2, n);
        sum_nn += a;
        sum_r += b;
        worse += b > a * 1.02;
        if (getenv("TM_VERBOSE"))
            fprintf(stderr, "n=%d nn=%.0f plan=%.0f\n", n, a, b);
    }
    CHECK(sum_r < 0.95 * sum_nn);
    CHECK(worse <= 2);
}

void route_is_deterministic(void)
{
    gd_point s = {10, -20};
    gd_point q[50];
    for (int i = 0; i < 50; i++)   /* a grid: many equal distances, ties everywhere */
        q[i] = (gd_point){(i % 7) * 30.0, (i / 7) * 30.0};
    int a[50], b[50];
    tm_route_plan(s, q, 50, a);
    tm_route_plan(s, q, 50, b);
    CHECK(!memcmp(a, b, sizeof a));
    int seen[50] = {0};
    for (int i = 0; i < 50; i++)
        seen[a[i]]++;
    for (int i = 0; i < 50; i++)
        CHECK(seen[i] == 1);
    tm_route_plan(s, q, 0, a);   /* nothing to plan is fine */
    tm_route_plan(s, q, 1, a);
    CHECK(a[0] == 0);
}

void roster_and_lines_parse(void)
{
    tm_roster r;
    char why[160];
    CHECK(tm_roster_parse(&r, "AUV1, AUV2,AUV3 ,AUV4", why, sizeof why) == 0 && r.n == 4);
    CHECK(tm_roster_index(&r, "AUV3") == 2 && tm_roster_index(&r, "AUV9") == -1);
    CHECK(tm_roster_parse(&r, "AUV1,,AUV2", why, sizeof why) == -1);
    CHECK_HAS(why, "at character 6: expected a vehicle name");
    CHECK(tm_roster_parse(&r, "AUV1,AUV1", why, sizeof why) == -1);
    CHECK_HAS(why, "vehicle named twice");
    CHECK(tm_roster_parse(&r, "", why, sizeof why) == -1);
    CHECK(tm_roster_parse(&r, "A B", why, sizeof why) == -1);
    CHECK_HAS(why, "at character 3: expected ','");
    CHECK(tm_roster_parse(&r, "A,B,C,D,E,F,G,H,I,J,K,L,M,N,O,P,Q", why, sizeof why) == -1);
    CHECK_HAS(why, "more than 16");

    tm_lines l;
    CHECK(tm_lines_parse(&l, "0: 0,0 0,400; 0: 20,400 20,0; 1: 40,0 40,400;", 4, why, sizeof why) == 0);
    CHECK(l.n == 3 && l.l[1].owner == 0 && l.l[1].a.n == 20 && l.l[1].b.e == 0 && l.l[2].owner == 1);
    CHECK(tm_lines_parse(&l, "0: 0,0 0,400; 5: 1,1 2,2", 4, why, sizeof why) == -1);
    CHECK_HAS(why, "at character 15: owner is not a team index");
    CHECK(tm_lines_parse(&l, "0: 0,0 0;400", 4, why, sizeof why) == -1);
    CHECK_HAS(why, "expected ',' between north and east");
    CHECK(tm_lines_parse(&l, "0 0,0 0,1", 4, why, sizeof why) == -1);
    CHECK_HAS(why, "expected ':'");
    CHECK(tm_lines_parse(&l, "0: 0,nan 0,1", 4, why, sizeof why) == -1);
    CHECK(tm_lines_parse(&l, "0: 0,0 0,1 x", 4, why, sizeof why) == -1);
    CHECK_HAS(why, "expected ';'");
    CHECK(tm_lines_parse(&l, "", 4, why, sizeof why) == -1);
}

/* Lines 0..9: vehicle 0 owns 0-3, vehicle 1 owns 4-6, vehicle 2 owns 7-9;
 * vehicle 3 (the RI vehicle) owns none. */
static const char *TEN =
    "0: 0,0 0,1; 0: 1,0 1,1; 0: 2,0 2,1; 0: 3,0 3,1; 1: 4,0 4,1; 1: 5,0 5,1; 1: 6,0 6,1; "
    "2: 7,0 7,1; 2: 8,0 8,1; 2: 9,0 9,1";

void takeover_round_robin_in_line_order(void)
{
    tm_lines l;
    static tm_work w, w2;
    char why[160];
    CHECK(tm_lines_parse(&l, TEN, 4, why, sizeof why) == 0);
    CHECK(tm_is_searcher(&l, 2) && !tm_is_searcher(&l, 3));
    int alive[4] = {1, 0, 1, 1}, to[TM_MAX_LINES];
    /* vehicle 0 lost after reporting next_line 1, vehicle 1 lost too: 2 takes lines 1, 2, 3 */
    tm_work_init(&w, &l, 4);
    CHECK(w.n[0] == 4 && w.n[1] == 3 && w.n[2] == 3 && w.n[3] == 0);
    CHECK(tm_takeover_deal(&w, &l, 0, 1, alive, 4, to) == 3);
    CHECK(to[0] == -1 && to[1] == 2 && to[2] == 2 && to[3] == 2 && to[4] == -1);
    CHECK(w.n[2] == 6 && w.line[2][3] == 1 && w.line[2][5] == 3);   /* appended in the order dealt */
    /* vehicle 0 lost at its start, 1 and 2 alive; the RI vehicle 3 never takes lines */
    int all[4] = {1, 1, 1, 1};
    tm_work_init(&w, &l, 4);
    CHECK(tm_takeover_deal(&w, &l, 0, 0, all, 4, to) == 4);
    CHECK(to[0] == 1 && to[1] == 2 && to[2] == 1 && to[3] == 2);
    /* every vehicle computes the same deal from the same heard facts: the
     * function depends on nothing else (same inputs, same output) */
    int to2[TM_MAX_LINES];
    tm_work_init(&w2, &l, 4);
    tm_takeover_deal(&w2, &l, 0, 0, all, 4, to2);
    CHECK(!memcmp(to, to2, sizeof to) && !memcmp(&w, &w2, sizeof w));
    /* then vehicle 1, which took lines 0 and 2, is lost having flown its
     * three own lines and line 0 (next_line 4): line 2 goes on to vehicle 2,
     * the one survivor, after what it already has */
    int alive2[4] = {0, 0, 1, 1};
    CHECK(tm_takeover_deal(&w, &l, 1, 4, alive2, 4, to) == 1);
    CHECK(to[2] == 2 && to[0] == -1 && w.n[2] == 6 && w.line[2][5] == 2);
    /* all flown (next_line at or past the end, 63 on the link) deals nothing; no survivor deals nothing */
    tm_work_init(&w, &l, 4);
    CHECK(tm_takeover_deal(&w, &l, 1, TM_ALL_DONE, all, 4, to) == 0);
    int none[4] = {0, 0, 0, 1};
    CHECK(tm_takeover_deal(&w, &l, 2, 0, none, 4, to) == 0);
    for (int i = 0; i < l.n; i++)
        CHECK(to[i] == -1);
}

void tdma_slots_from_the_clock(void)
{
    tm_tdma t;
    tm_tdma_init(&t, 5.0, 4, 2, 1.0);   /* slot 2 of 4: [10, 11) s of each 20 s round */
    CHECK(tm_tdma_slot(&t, 0) == 0 && tm_tdma_slot(&t, 10000000) == 2 && tm_tdma_slot(&t, 19999999) == 3);
    CHECK(tm_tdma_slot(&t, 20000000) == 0);
    CHECK(tm_tdma_may_send(&t, 9999999) == -1);
    CHECK(tm_tdma_may_send(&t, 10000000) == 0);
    CHECK(tm_tdma_may_send(&t, 10999999) == 0);
    CHECK(tm_tdma_may_send(&t, 11000000) == -1);   /* too late in the slot: the frame would overrun it */
    tm_tdma_sent(&t, 0);
    CHECK(tm_tdma_may_send(&t, 10500000) == -1);   /* once per round */
    CHECK(tm_tdma_may_send(&t, 30100000) == 1);
    CHECK(tm_tdma_may_send(&t, 1000000000LL * 3600 + 10000000) == 180000);   /* an hour on, no drift */
    /* two vehicles with different slots never share a send window */
    tm_tdma a, b;
    tm_tdma_init(&a, 5.0, 4, 0, 5.0);
    tm_tdma_init(&b, 5.0, 4, 1, 5.0);
    int both = 0;
    for (int64_t us = 0; us < 100000000; us += 100000)
        both += tm_tdma_may_send(&a, us) >= 0 && tm_tdma_may_send(&b, us) >= 0;
    CHECK(both == 0);
}

/* A stub frame: each item kind has a size in bits; the frame holds cap bits.
 * Contact number 99 cannot be encoded (out of range). */
typedef struct {
    int cap, used;
} stub_frame;

static int stub_put(void *user, const tm_item *it)
{
    stub_frame *f = user;
    static const int bits[] = {0, 22, 80, 84, 80};
    if (it->kind == TM_ITEM_CONTACT && it->a == 99)
        return -1;
    if (f->used + bits[it->kind] > f->cap)
        return 0;
    f->used += bits[it->kind];
    return 1;
}

static int count_kind(const tm_item *it, int n, tm_item_kind k)
{
    int c = 0;
    for (int i = 0; i < n; i++)
        c += it[i].kind == k;
    return c;
}

void outbox_priorities(void)
{
    static tm_outbox o;
    tm_outbox_init(&o, 2);
    stub_frame f = {256, 0};
    tm_frame_writer w = {stub_put, &f};
    tm_item put[32];
    for (int i = 0; i < 4; i++)
        tm_outbox_contact(&o, i);
    tm_outbox_status(&o);
    tm_outbox_ack(&o, 2, 7);
    tm_outbox_ack(&o, 2, 7);   /* one ack per pending report */
    /* 22 + 84 + 84 = 190; status (80) does not fit, a third contact does not either */
    int n = tm_outbox_fill(&o, &w, put, 32);
    CHECK(n == 3 && put[0].kind == TM_ITEM_ACK && put[0].a == 2 && put[0].b == 7);
    CHECK(put[1].kind == TM_ITEM_CONTACT && put[1].a == 0 && put[2].kind == TM_ITEM_CONTACT && put[2].a == 1);
    CHECK(o.n_acks == 0 && o.status_pending == 1);
    /* next frame: the contacts not yet sent go first (fewest sends), then
     * one sent once (still below repeat = 2, so still before the status) */
    f.used = 0;
    n = tm_outbox_fill(&o, &w, put, 32);
    CHECK(n == 3 && put[0].a == 2 && put[1].a == 3 && put[2].kind == TM_ITEM_CONTACT && put[2].a == 0);
    CHECK(o.status_pending == 1);
    /* contact 0 acked: never sent again; the others reach `repeat` sends and
     * fall behind the status */
    CHECK(tm_outbox_acked(&o, 0) == 1 && tm_outbox_acked(&o, 0) == 0);
    f.used = 0;
    n = tm_outbox_fill(&o, &w, put, 32);   /* 1 (1 send), then 2, 3: 84 * 3 = 252 */
    CHECK(n == 3 && put[0].a == 1 && count_kind(put, n, TM_ITEM_STATUS) == 0);
    tm_outbox_status(&o);
    f.used = 0;
    n = tm_outbox_fill(&o, &w, put, 32);   /* all at repeat now: status first, then still resent */
    CHECK(put[0].kind == TM_ITEM_STATUS && count_kind(put, n, TM_ITEM_CONTACT) == 2);
    CHECK(tm_outbox_unacked(&o) == 3);
    /* idents go before contacts, each `repeat` times */
    int id = tm_outbox_ident(&o);
    CHECK(id == 0);
    for (int k = 0; k < 3; k++) {
        f.used = 0;
        n = tm_outbox_fill(&o, &w, put, 32);
        CHECK(count_kind(put, n, TM_ITEM_IDENT) == (k < 2));
        if (k < 2)
            CHECK(put[0].kind == TM_ITEM_IDENT);
    }
    /* a contact the encoder refuses is counted and dropped, the rest still go */
    tm_outbox_contact(&o, 99);
    f.used = 0;
    long before = o.refused;
    n = tm_outbox_fill(&o, &w, put, 32);
    CHECK(o.refused == before + 1 && count_kind(put, n, TM_ITEM_CONTACT) >= 1);
    CHECK(tm_outbox_unacked(&o) == 3);
}

/* Contact reports over a link that loses 30 % of frames (both ways): a search
 * vehicle with 12 mine-like contacts, one frame per round each way; the RI
 * side acks what it hears. Every contact arrives and is acked, in rounds
 * bounded well below a mission's length, whatever the loss pattern. */
void reports_survive_30_percent_loss(void)
{
    for (int seed = 1; seed <= 20; seed++) {
        rng = 0x9E3779B97F4A7C15ull * (uint64_t)seed;
        static tm_outbox search, ri;
        tm_outbox_init(&search, 3);
        tm_outbox_init(&ri, 3);
        int heard[12] = {0}, acked_at = -1;
        for (int i = 0; i < 12; i++)
            tm_outbox_contact(&search, i);
        for (int round = 0; round < 200 && acked_at < 0; round++) {
            tm_outbox_status(&search);
            tm_outbox_status(&ri);
            stub_frame f = {256, 0};
            tm_frame_writer w = {stub_put, &f};
            tm_item put[32];
            int n = tm_outbox_fill(&search, &w, put, 32);
            if (uniform() >= 0.3)   /* frame heard by the RI vehicle */
                for (int i = 0; i < n; i++)
                    if (put[i].kind == TM_ITEM_CONTACT) {
                        heard[put[i].a] = 1;
                        tm_outbox_ack(&ri, 0, put[i].a);
                    }
            f.used = 0;
            n = tm_outbox_fill(&ri, &w, put, 32);
            if (uniform() >= 0.3)
                for (int i = 0; i < n; i++)
                    if (put[i].kind == TM_ITEM_ACK)
                        tm_outbox_acked(&search, put[i].b);
            if (tm_outbox_unacked(&search) == 0)
                acked_at = round;
        }
        for (int i = 0; i < 12; i++)
            CHECK(heard[i]);
        CHECK(acked_at >= 0 && acked_at < 40);
    }
}

void keep_clear_cpa(void)
{
    /* head-on, 200 m apart at 1.5 m/s each: they meet in 66.7 s */
    tm_track a = {0, 0, 0, 1.5}, b = {200, 0, M_PI, 1.5};
    double t;
    CHECK_NEAR(tm_cpa(a, b, 100, &t), 0, 1e-9);
    CHECK_NEAR(t, 200 / 3.0, 1e-6);
    CHECK_NEAR(tm_cpa(a, b, 30, &t), 110, 1e-9);   /* not within the horizon */
    /* crossing at right angles, offset: b crosses a's track 10 m behind it */
    tm_track c = {-10, 50, -M_PI / 2, 1.5};
    double d = tm_cpa(a, c, 100, &t);
    CHECK(d > 6 && d < 50);
    /* diverging: the closest is now */
    tm_track e = {0, 20, M_PI / 2, 1.5};
    CHECK_NEAR(tm_cpa(a, e, 100, &t), 20, 1e-9);
    tm_track f = tm_track_advance(b, 10);
    CHECK_NEAR(f.n, 185, 1e-9);
}


/* The sampling rule: the least certain place along the front is the one
 * farthest from every look at it (tm_front_rule.h), and the team shares the
 * places out, the least certain to the nearest vehicle first. */
void front_rule_picks_the_least_certain_place(void)
{
    static tm_fr_looks looks;
    memset(&looks, 0, sizeof looks);
    tm_fr_front f = {0.0, 0.0};   /* the front runs north along east = 0 */
    for (double s = 0; s <= 100; s += 10)
        tm_fr_add(&looks, s, (int)s % 20 ? 15.0 : -15.0);   /* own zig-zag across it */
    double mate = 400;                                     /* a teammate looking at 400 m now */
    /* cells of 50 m over [0, 600]: centres 25 .. 575; 575 is 175 m from the teammate, 250 is 150 from either */
    CHECK_NEAR(tm_fr_pick(&looks, &f, 60, &mate, 1, 0, 600, 50, 100), 575, 1e-9);
    CHECK_NEAR(tm_fr_uncertainty(&looks, &f, 60, &mate, 1, 575), 175, 1e-9);
    /* a position far from the front is no look at it */
    tm_fr_add(&looks, 575, 200);
    CHECK_NEAR(tm_fr_pick(&looks, &f, 60, &mate, 1, 0, 600, 50, 100), 575, 1e-9);
    /* one near it is: the gap between the vehicle and its teammate is now the least certain, its
     * two middle cells (225, 275) 125 m from a look each: the tie goes to the nearer */
    tm_fr_add(&looks, 575, -10);
    CHECK_NEAR(tm_fr_pick(&looks, &f, 60, &mate, 1, 0, 600, 50, 100), 225, 1e-9);
    CHECK_NEAR(tm_fr_pick(&looks, &f, 60, &mate, 1, 0, 600, 50, 390), 275, 1e-9);
    /* the same world seen along a rotated front gives the same answer (the rule is geometry, not axes) */
    static tm_fr_looks turned;
    memset(&turned, 0, sizeof turned);
    double a = 0.7, off = 40;
    tm_fr_front g = {a, off};
    for (int i = 0; i < looks.n; i++) {
        tm_fr_point p = looks.pts[i];   /* (s, x) in the first front's frame -> north, east */
        tm_fr_add(&turned, p.n * cos(a) - (p.e + off) * sin(a), p.n * sin(a) + (p.e + off) * cos(a));
    }
    CHECK_NEAR(tm_fr_pick(&turned, &g, 60, &mate, 1, 0, 600, 50, 100), 225, 1e-6);
    /* nobody has looked anywhere: every cell ties, the nearest wins */
    static tm_fr_looks none;
    memset(&none, 0, sizeof none);
    CHECK_NEAR(tm_fr_pick(&none, &f, 60, NULL, 0, 0, 600, 50, 333), 325, 1e-9);
    /* three vehicles at 0, 250, 500 along an unseen front [0, 800]: the far end (775, 275 m
     * from the nearest) goes to the vehicle at 500; then the gaps halfway, each to the nearer */
    double pos[3] = {0, 250, 500}, tg[3];
    tm_fr_assign(&none, &f, 60, pos, 3, 0, 800, 50, tg);
    CHECK_NEAR(tg[2], 775, 1e-9);
    CHECK(tg[0] >= 75 && tg[0] <= 175);    /* between 0 and 250 */
    CHECK(tg[1] >= 325 && tg[1] <= 425);   /* between 250 and 500 */
    printf("# targets of vehicles at 0, 250, 500 m: %.0f, %.0f, %.0f m\n", tg[0], tg[1], tg[2]);
    /* every vehicle computes the same assignment from the same data */
    double again[3];
    tm_fr_assign(&none, &f, 60, pos, 3, 0, 800, 50, again);
    CHECK(again[0] == tg[0] && again[1] == tg[1] && again[2] == tg[2]);
    /* the record is bounded: the oldest looks go first, and are counted */
    for (int i = 0; i < TM_FR_MAX_POINTS + 52; i++)
        tm_fr_add(&none, i, 0);
    CHECK(none.n == TM_FR_MAX_POINTS && none.dropped == 52);
    tm_fr_add(&none, NAN, 0);   /* not a position: not recorded */
    CHECK(none.dropped == 52);
}
