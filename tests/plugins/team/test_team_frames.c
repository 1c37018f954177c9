/* The team link's frames end to end without an engine: two stores (a search
 * vehicle and the RI vehicle) exchange frames built by tm_frame_build and
 * applied by tm_frame_receive through the generated codec; hostile frames are
 * counted, never crash. (The plugin's shared store is a singleton; these
 * tests use their own stores.) */
#include <math.h>
#include <stdlib.h>

#include "../common/plugin_test.h"
#include "team_tests.h"
#include "plugins/team/tm_frame.h"
#include "teamlink/team_front.h"

static tm_store a_store, b_store;

/* AUV1 (index 0, search) and AUV4 (index 3, RI) at mission time t. */
static void two_vehicles(double t)
{
    tm_roster r;
    char why[128];
    tm_roster_parse(&r, "AUV1,AUV2,AUV3,AUV4", why, sizeof why);
    memset(&a_store, 0, sizeof a_store);
    memset(&b_store, 0, sizeof b_store);
    tm_store_configure(&a_store, &r, 0, (int64_t)(t * 1e6), 3);
    tm_store_configure(&b_store, &r, 3, (int64_t)(t * 1e6), 3);
    b_store.is_ri = 1;
}

static int count_events(const tm_store *s, int kind)
{
    int n = 0;
    for (int i = 0; i < s->n_events; i++)
        n += s->events[i].kind == kind;
    return n;
}

static void add_contact(tm_store *s, double n, double e, double score)
{
    int created;
    int i = tm_contacts_add(&s->contacts, n, e, 1.5, score, 0, 5, &created);
    s->contacts.c[i].queued = 1;
    tm_outbox_contact(&s->out, i);
}

void frames_carry_contacts_acks_and_status(void)
{
    two_vehicles(100);
    add_contact(&a_store, 120.25, -40.5, 0.8);
    add_contact(&a_store, 300, 200, 0.7);
    add_contact(&a_store, -310, 20, 0.9);
    a_store.own = (tm_track){50, 60, 1.0, 1.5};
    a_store.t_own = 118.0;   /* team_status ran 2 s before the frame at 120 s */
    a_store.own_depth = 8.0;
    a_store.next_line = 2;
    a_store.status_state = TM_ST_SURVEY;
    tm_outbox_status(&a_store.out);
    uint8_t buf[32];
    tm_item put[16];
    int n;
    size_t len = tm_frame_build(&a_store, 100000000, buf, 32, put, 16, &n);
    /* three contacts of 78 bits (234 bits, 30 bytes) leave no room for a status */
    CHECK(n == 3 && len == 30 && a_store.out.status_pending == 1);
    CHECK(tm_frame_receive(&b_store, 0, buf, len, 102000000) == 3);
    CHECK(b_store.targets.n == 3 && b_store.out.n_acks == 3 && b_store.targets_changed == 1);
    CHECK_NEAR(b_store.targets.t[0].n, 120.25, 1e-9);
    CHECK_NEAR(b_store.targets.t[0].e, -40.5, 1e-9);
    CHECK(count_events(&b_store, TM_EV_TARGET_QUEUED) == 3);
    /* the RI vehicle's frame: three acks (54 bits) and its status */
    b_store.own = (tm_track){0, 0, 0, 1.0};
    b_store.t_own = 105.0;
    tm_outbox_status(&b_store.out);
    len = tm_frame_build(&b_store, 105000000, buf, 32, put, 16, &n);
    CHECK(n == 4 && put[0].kind == TM_ITEM_ACK && put[3].kind == TM_ITEM_STATUS);
    CHECK(tm_frame_receive(&a_store, 3, buf, len, 106000000) == 4);
    CHECK(count_events(&a_store, TM_EV_CONTACT_ACKED) == 3 && tm_outbox_unacked(&a_store.out) == 0);
    CHECK(a_store.peer[3].has_status && a_store.peer[3].state == 0);
    CHECK_NEAR(a_store.peer[3].t_status, 105, 1e-9);
    /* the next frame of AUV1 is its status alone, which AUV4 reads back */
    len = tm_frame_build(&a_store, 120000000, buf, 32, put, 16, &n);
    CHECK(n == 1 && put[0].kind == TM_ITEM_STATUS);
    tm_frame_receive(&b_store, 0, buf, len, 121000000);
    const tm_peer *p = &b_store.peer[0];
    CHECK(p->has_status && p->next_line == 2 && p->state == TM_ST_SURVEY);
    /* where AUV1 was at the stamp: its fix of 118 s dead-reckoned 2 s on */
    CHECK_NEAR(p->track.n, 50 + 3 * cos(1.0), 0.5);
    CHECK_NEAR(p->track.e, 60 + 3 * sin(1.0), 0.5);
    CHECK_NEAR(p->track.heading, 1.0, 0.0125);
    CHECK_NEAR(p->depth, 8.0, 0.05);
    CHECK_NEAR(p->t_status, 120, 1e-9);
}

void repeats_are_acked_again_and_merged_once(void)
{
    two_vehicles(0);
    add_contact(&a_store, 10, 10, 0.8);
    uint8_t buf[32];
    tm_item put[16];
    int n;
    size_t len = tm_frame_build(&a_store, 0, buf, 32, put, 16, &n);
    tm_frame_receive(&b_store, 0, buf, len, 1000000);
    len = tm_frame_build(&b_store, 5000000, buf, 32, put, 16, &n);   /* the ack ... lost */
    CHECK(n == 1 && b_store.out.n_acks == 0);
    len = tm_frame_build(&a_store, 20000000, buf, 32, put, 16, &n);  /* the repeat */
    CHECK(n == 1 && put[0].kind == TM_ITEM_CONTACT);
    tm_frame_receive(&b_store, 0, buf, len, 21000000);
    CHECK(b_store.targets.n == 1 && b_store.out.n_acks == 1 && count_events(&b_store, TM_EV_TARGET_QUEUED) == 1);
    /* another vehicle's report of the same object 2 m away: an alias */
    tm_store c_store;
    memcpy(&c_store, &a_store, sizeof c_store);
    c_store.me = 1;
    len = tm_frame_build(&c_store, 25000000, buf, 32, put, 16, &n);
    tm_frame_receive(&b_store, 1, buf, len, 26000000);
    CHECK(b_store.targets.n == 1 && b_store.targets.t[0].n_alias == 1 && b_store.out.n_acks == 2);
}

void hostile_frames_are_counted(void)
{
    two_vehicles(0);
    uint8_t junk[64];
    uint64_t x = 12345;
    long bad = 0;
    for (int k = 0; k < 2000; k++) {
        size_t len = (size_t)(k % 40);
        for (size_t i = 0; i < len; i++) {
            x = x * 6364136223846793005ull + 1442695040888963407ull;
            junk[i] = (uint8_t)(x >> 56);
        }
        if (tm_frame_receive(&b_store, 1 + k % 2, junk, len, (int64_t)k * 1000000) < 0)
            bad++;
    }
    CHECK(bad > 0 && b_store.frames_bad == bad);
    /* whatever was accepted stays inside the tables */
    CHECK(b_store.targets.n <= TM_MAX_TARGETS && b_store.out.n_acks <= TM_MAX_ACKS);
    /* a status that claims to be another vehicle than its sender is ignored */
    two_vehicles(0);
    a_store.status_state = 1;
    tm_outbox_status(&a_store.out);
    uint8_t buf[32];
    tm_item put[4];
    int n;
    size_t len = tm_frame_build(&a_store, 0, buf, 32, put, 4, &n);
    tm_frame_receive(&b_store, 2, buf, len, 0);
    CHECK(!b_store.peer[2].has_status && !b_store.peer[0].has_status);
    /* a contact outside the schema's range is refused and counted, the
     * others still go */
    two_vehicles(0);
    add_contact(&a_store, 5000, 0, 0.9);
    add_contact(&a_store, 10, 0, 0.9);
    len = tm_frame_build(&a_store, 0, buf, 32, put, 4, &n);
    CHECK(n == 1 && put[0].a == 1 && a_store.out.refused == 1);
    CHECK(tm_outbox_unacked(&a_store.out) == 1);
}

void time_stamps_unwrap(void)
{
    CHECK_NEAR(tm_time_unwrap(100, 105.4), 100, 1e-9);
    CHECK_NEAR(tm_time_unwrap(16380, 16384 + 3.0), 16380, 1e-9);   /* across the 14-bit wrap */
    CHECK_NEAR(tm_time_unwrap(5, 3 * 16384 + 10.0), 3 * 16384 + 5, 1e-9);
}


/* A sampling vehicle's own front estimate rides its frames once, after the
 * status, with each sigma rounded up to its step (teamlink/team_front.h);
 * one outside the schema's ranges is not made at all. */
void frames_carry_the_front_summary(void)
{
    two_vehicles(0);
    team_front_estimate e = {0, 250.7, 301.26, 0.2004, 15.993, 12.004, 20.13, 0.31, 0.0012, 0.0021, 0.0034, 0.44, 400};
    team_msg_front f;
    CHECK(team_front_summary(&e, &f) == 1);
    CHECK(f.time_s == 250 && f.samples == 400);
    CHECK_NEAR(f.offset_sigma_m, 0.4, 1e-9);   /* 0.31 up to its 0.1 m step */
    CHECK_NEAR(f.angle_sigma, 0.002, 1e-9);
    CHECK_NEAR(f.temp_sigma_c, 0.004, 1e-9);   /* the larger water's, up */
    CHECK_NEAR(f.width_sigma_m, 0.5, 1e-9);
    a_store.own_front = f;
    a_store.has_own_front = 1;
    a_store.status_state = TM_ST_SURVEY;
    tm_outbox_status(&a_store.out);
    tm_outbox_front(&a_store.out);
    uint8_t buf[32];
    tm_item put[8];
    int n;
    size_t len = tm_frame_build(&a_store, 251000000, buf, 32, put, 8, &n);
    CHECK(n == 2 && put[0].kind == TM_ITEM_STATUS && put[1].kind == TM_ITEM_FRONT);
    CHECK(len == 26);   /* a status's 10 bytes and the front's 16 (127 + 77 bits -> 26 bytes) */
    team_bits r;
    team_bits_reader(&r, buf, len);
    team_msg m;
    CHECK(team_decode_next(&r, &m) == TEAM_MSG_STATUS);
    CHECK(team_decode_next(&r, &m) == TEAM_MSG_FRONT);
    CHECK_NEAR(m.u.front.offset_m, 301.26, 0.25 + 1e-9);   /* half of its 0.5 m step */
    CHECK_NEAR(m.u.front.angle, 0.2004, 0.0005 + 1e-9);
    CHECK_NEAR(m.u.front.offset_sigma_m, 0.4, 1e-9);
    CHECK(tm_frame_receive(&b_store, 0, buf, len, 251000000) == 2 && b_store.fronts_heard == 1);
    /* sent once: the next frame has none until a new estimate comes */
    tm_outbox_status(&a_store.out);
    len = tm_frame_build(&a_store, 271000000, buf, 32, put, 8, &n);
    CHECK(n == 1 && put[0].kind == TM_ITEM_STATUS);
    /* a sigma beyond the field's 25.5 m, a NaN: not sendable */
    e.offset_sigma_m = 30;
    CHECK(team_front_summary(&e, &f) == 0);
    e.offset_sigma_m = 0.3;
    e.width_m = NAN;
    CHECK(team_front_summary(&e, &f) == 0);
}
