/* The team plugin in plans loaded by the real libchasm, one vehicle per
 * test (the plugin keeps one store per process, as a manager runs one plan):
 * its teammates are hand-made frames fed into modem_rx, and what it says is
 * read back from modem_tx and team_events, decoded. Line numbers: the
 * prelude is 17 lines, so a plan body starts on line 18. */
#include "team_plan_kit.h"
#include "team_tests.h"

#define ROSTER "team = \"AUV1,AUV2,AUV3,AUV4\""

void plan_refuses_bad_roster_and_lines(void)
{
    const char *e = team_errors("state s {\n    do team_link(team = \"AUV1,,AUV2\", me = \"AUV1\")\n}\n");
    CHECK_HAS(e, "t.chasm:19:");
    CHECK_HAS(e, "parameter 'team' of 'team_link': at character 6: expected a vehicle name");
    e = team_errors("state s {\n    do team_link(" ROSTER ", me = \"AUV9\")\n}\n");
    CHECK_HAS(e, "parameter 'me' of 'team_link': 'AUV9' is not in the team roster");
    e = team_errors("state s {\n    do team_link(" ROSTER ", me = \"AUV1\", slots = 4, my_slot = 4)\n}\n");
    CHECK_HAS(e, "parameter 'my_slot' of 'team_link': slot 4 does not exist: slots = 4");
    e = team_errors("state s {\n    do team_link(" ROSTER ", me = \"AUV1\")\n"
                    "    state a {\n        do team_survey(lines = \"0: 0,0 10,0; 1 0,0 1,1\")\n    }\n}\n");
    CHECK_HAS(e, "t.chasm:21:");
    CHECK_HAS(e, "parameter 'lines' of 'team_survey': at character 16: expected ':' after the owner");
    e = team_errors("state s {\n    do team_link(" ROSTER ", me = \"AUV1\", repeat = 0)\n}\n");
    CHECK_HAS(e, "repeat");
}

/* Steps at 10 Hz from t0 to t1 with the vehicle standing at (n, e). */
static void run(chasm_machine *m, double t0, double t1, double n, double e)
{
    for (double t = t0; t < t1 - 1e-9; t += 0.1) {
        team_nav(m, n, e, 0, 1.5, t);
        pt_step(m, t);
    }
}

void search_vehicle_reports_until_acked(void)
{
    chasm_machine *m = team_load("state mission {\n"
                                 "    do team_link(" ROSTER ", me = \"AUV1\", my_slot = 0)\n"
                                 "    do team_status() every 20 s\n"
                                 "    do search_contacts(min_score = 0.5)\n"
                                 "}\n");
    if (!m)
        return;
    team_nav(m, 0, 0, 0, 1.5, 0);
    pt_start(m, 0);
    team_feed_contact(m, 0, 100, 50, 0.8, 1.0);
    team_feed_contact(m, 1, 101, 50, 0.7, 1.0);   /* a second look: merged */
    team_feed_contact(m, 2, 300, 300, 0.2, 1.0);  /* clutter */
    run(m, 0.1, 19.9, 0, 0);
    team_ev ev[64];
    int n_ev = team_take_events(m, ev, 64);
    CHECK(team_count(ev, n_ev, 1 /* CONTACT_NEW */) == 1);
    const team_ev *k = team_find(ev, n_ev, 1);
    CHECK(k && k->number == 0 && !strcmp(k->origin, "AUV1"));
    if (k)   /* mine-like from its first look */
        CHECK_NEAR(k->n, 100, 1e-6);
    team_msg msgs[32];
    int frames;
    team_take_frames(m, msgs, 32, &frames);
    /* round 1 (t = 20 s, slot 0): the contact before the status */
    run(m, 19.9, 21, 0, 0);
    int n = team_take_frames(m, msgs, 32, &frames);
    CHECK(frames == 1 && n == 2 && msgs[0].id == TEAM_MSG_CONTACT && msgs[1].id == TEAM_MSG_STATUS);
    if (n >= 1 && msgs[0].id == TEAM_MSG_CONTACT) {
        CHECK(msgs[0].u.contact.origin == 0 && msgs[0].u.contact.number == 0 && msgs[0].u.contact.looks == 2);
        CHECK_NEAR(msgs[0].u.contact.score, 0.75, 0.006);
    }
    /* not acked: repeated at round 2 */
    run(m, 21, 41, 0, 0);
    n = team_take_frames(m, msgs, 32, &frames);
    CHECK(frames == 1 && n >= 1 && msgs[0].id == TEAM_MSG_CONTACT);
    /* AUV4 acks it: CONTACT_ACKED, and round 3 carries the status only */
    team_msg ack = {.id = TEAM_MSG_ACK, .u.ack = {0, 0}};
    team_feed_frame(m, "AUV1", "AUV4", &ack, 1, 45);
    run(m, 41, 61, 0, 0);
    n = team_take_frames(m, msgs, 32, &frames);
    CHECK(frames == 1 && n == 1 && msgs[0].id == TEAM_MSG_STATUS);
    n_ev = team_take_events(m, ev, 64);
    CHECK(team_count(ev, n_ev, 3 /* CONTACT_ACKED */) == 1);
    CHECK(team_count(ev, n_ev, 2 /* CONTACT_SENT */) == 2);   /* rounds 1 and 2 */
    chasm_free(m);
}

static team_msg contact(int origin, int number, double n, double e)
{
    return (team_msg){.id = TEAM_MSG_CONTACT, .u.contact = {origin, number, n, e, 1.0, 0.8, 2, 1}};
}

static team_msg status(int vehicle, double n, double e, double heading, int next_line, int state, int t)
{
    return (team_msg){.id = TEAM_MSG_STATUS, .u.status = {vehicle, t, n, e, 5, heading, 1.5, next_line, state}};
}

void ri_vehicle_merges_routes_and_identifies(void)
{
    chasm_machine *m = team_load("state mission {\n"
                                 "    do team_link(" ROSTER ", me = \"AUV4\", my_slot = 3)\n"
                                 "    do team_status() every 20 s\n"
                                 "    state work {\n"
                                 "        do ri_reacquire(speed = 1.5 m/s, depth = 5 m)\n"
                                 "        when done -> finished\n"
                                 "    }\n"
                                 "    state finished {\n"
                                 "    }\n"
                                 "}\n");
    if (!m)
        return;
    team_nav(m, 0, 0, 0, 1.5, 0);
    pt_start(m, 0);
    team_msg a[2] = {contact(0, 0, 100, 0), contact(0, 1, -50, 0)};
    team_feed_frame(m, "AUV4", "AUV1", a, 2, 1);
    team_msg b = contact(1, 5, 102, 0);   /* AUV2 saw AUV1's first object */
    team_feed_frame(m, "AUV4", "AUV2", &b, 1, 2);
    run(m, 0.1, 14.9, 0, 0);
    team_ev ev[64];
    int n_ev = team_take_events(m, ev, 64);
    CHECK(team_count(ev, n_ev, 4 /* TARGET_QUEUED */) == 2);
    CHECK(team_count(ev, n_ev, 7 /* ROUTE */) >= 1);
    /* the best open path from (0, 0) goes to (-50, 0) first: south */
    CHECK_NEAR(pt_get(m, "setpoint.heading_rad"), M_PI, 0.05);
    CHECK_NEAR(pt_get(m, "setpoint.depth_m"), 5, 1e-9);
    /* slot 3 (t = 15 s): the three reports acked, then the status */
    team_msg msgs[32];
    int frames;
    run(m, 14.9, 16, 0, 0);
    int n = team_take_frames(m, msgs, 32, &frames);
    CHECK(frames == 1 && n == 4 && msgs[3].id == TEAM_MSG_STATUS);
    int acks = 0;
    for (int i = 0; i < n; i++)
        acks += msgs[i].id == TEAM_MSG_ACK;
    CHECK(acks == 3);
    /* at the target, looks of a 0.9 sensor: three agreeing looks leave a
     * 1/730 chance of a wrong call, more than the plan's 1e-3: the fourth decides */
    run(m, 16, 17, -48, 1);
    for (int k = 0; k < 3; k++)
        team_feed_look(m, -50.4, 0.2, 1, 17 + 0.2 * k);
    run(m, 17, 17.8, -48, 1);
    n_ev = team_take_events(m, ev, 64);
    CHECK(!team_find(ev, n_ev, 5 /* TARGET_IDENTIFIED */));
    team_feed_look(m, -50.4, 0.2, 1, 18);
    run(m, 18, 19, -48, 1);
    n_ev = team_take_events(m, ev, 64);
    const team_ev *id = team_find(ev, n_ev, 5 /* TARGET_IDENTIFIED */);
    CHECK(id && !strcmp(id->origin, "AUV1") && id->number == 1 && id->result == 1);
    CHECK(id && strstr(id->text, "after 4 looks"));
    /* the next target is the merged one, north */
    CHECK_NEAR(remainder(pt_get(m, "setpoint.heading_rad"), 2 * M_PI), 0.0, 0.1);
    run(m, 19, 36, -48, 1);
    n = team_take_frames(m, msgs, 32, &frames);
    CHECK(n >= 1 && msgs[0].id == TEAM_MSG_IDENT && msgs[0].u.ident.origin == 0 && msgs[0].u.ident.number == 1 &&
          msgs[0].u.ident.result == 1);
    /* the search vehicles are done; the last target reached but never seen:
     * not found after the default look_timeout (180 s), then done */
    for (int v = 0; v < 3; v++) {
        team_msg st = status(v, 0, 0, 0, 63, 4, 40);
        team_feed_frame(m, "AUV4", v == 0 ? "AUV1" : v == 1 ? "AUV2" : "AUV3", &st, 1, 40);
    }
    run(m, 36, 150, 101, 0);
    n_ev = team_take_events(m, ev, 64);
    CHECK(!team_find(ev, n_ev, 6 /* TARGET_NOT_FOUND */));
    run(m, 150, 240, 101, 0);
    n_ev = team_take_events(m, ev, 64);
    const team_ev *nf = team_find(ev, n_ev, 6 /* TARGET_NOT_FOUND */);
    CHECK(nf && !strcmp(nf->origin, "AUV1") && nf->number == 0);
    CHECK_HAS(pt_leaf(m), "finished");
    chasm_free(m);
}

/* A vehicle flown by the plan's heading setpoint at 1.5 m/s, turning at most
 * as a REMUS 100 does (a loop some 28 m across), from (n, e, heading) over
 * [t0, t1) at 10 Hz; the number of separate passes within `range` of (tn, te). */
static int fly_turning(chasm_machine *m, double *n, double *e, double *h, double t0, double t1, double tn, double te,
                       double range)
{
    const double speed = 1.5, max_rate = speed / 14.0, dt = 0.1;
    int passes = 0, inside = 0;
    for (double t = t0; t < t1 - 1e-9; t += dt) {
        team_nav(m, *n, *e, *h, speed, t);
        pt_step(m, t);
        double err = remainder(pt_get(m, "setpoint.heading_rad") - *h, 2 * M_PI);
        double rate = fmax(-max_rate, fmin(max_rate, 0.5 * err));
        *h += rate * dt;
        *n += speed * cos(*h) * dt;
        *e += speed * sin(*h) * dt;
        int now = hypot(*n - tn, *e - te) <= range;
        passes += now && !inside;
        inside = now;
    }
    return passes;
}

/* A target reported abeam of the RI vehicle, inside its turning circle:
 * pursuit alone would circle it for ever some 10 m off, never in the
 * sensor's 6 m (the demo lost a target so). The vehicle must fly through it
 * in passes. */
void ri_vehicle_passes_through_a_target_inside_its_turning_circle(void)
{
    chasm_machine *m = team_load("state mission {\n"
                                 "    do team_link(" ROSTER ", me = \"AUV4\", my_slot = 3)\n"
                                 "    state work {\n"
                                 "        do ri_reacquire(speed = 1.5 m/s, depth = 5 m, look_timeout = 600 s)\n"
                                 "    }\n"
                                 "}\n");
    if (!m)
        return;
    double n = 0, e = 0, h = M_PI / 2;   /* heading east; the target 10 m to port */
    team_nav(m, n, e, h, 1.5, 0);
    pt_start(m, 0);
    team_msg a = contact(0, 0, 10, 0);
    team_feed_frame(m, "AUV4", "AUV1", &a, 1, 0.5);
    int passes = fly_turning(m, &n, &e, &h, 0.1, 300, 10, 0, 6.0);
    CHECK(passes >= 3);
    chasm_free(m);
}

static const char *LINES = "lines = \"0: 0,0 100,0; 0: 0,20 100,20; 0: 0,40 100,40; 1: 0,60 100,60; "
                           "2: 0,80 100,80; 2: 0,100 100,100\"";

/* A team member flying LINES: team_link(ROSTER, link_args), the `extra`
 * actions (lines ending in \n) beside it, started at (0, east) heading north;
 * NULL if the plan did not load. */
static chasm_machine *surveying(const char *link_args, const char *extra, double east)
{
    static char body[2048];
    snprintf(body, sizeof body,
             "state mission {\n"
             "    do team_link(" ROSTER ", %s)\n"
             "%s"
             "    state survey {\n"
             "        do team_survey(%s, depth = 10 m)\n"
             "    }\n"
             "}\n",
             link_args, extra, LINES);
    chasm_machine *m = team_load(body);
    if (!m)
        return NULL;
    team_nav(m, 0, east, 0, 1.5, 0);
    pt_start(m, 0);
    return m;
}

/* AUV2 (lost after 60 s of silence), sending its status every 20 s. */
static chasm_machine *auv2_surveying(void)
{
    return surveying("me = \"AUV2\", my_slot = 1, silent = 60 s", "    do team_status() every 20 s\n", 60);
}

void lost_teammates_lines_are_taken(void)
{
    chasm_machine *m = auv2_surveying();
    if (!m)
        return;
    team_msg s1 = status(0, 20, 0, 0, 1, 1, 5);   /* AUV1 flew line 0 */
    team_feed_frame(m, "AUV2", "AUV1", &s1, 1, 5);
    for (int t = 0; t <= 120; t += 20) {
        if (t < 70) {
            team_msg s3 = status(2, 0, 80, 0, 0, 1, t);
            team_feed_frame(m, "AUV2", "AUV3", &s3, 1, t + 0.5);
        }
        team_msg s4 = status(3, 0, 0, 0, 0, 3, t);
        team_feed_frame(m, "AUV2", "AUV4", &s4, 1, t + 0.5);
        run(m, t == 0 ? 0.1 : t, t + 20, 0, 60);
        if (t == 20)
            CHECK_NEAR(pt_get(m, "setpoint.heading_rad"), 0.0, 0.05);   /* along its own line, north */
    }
    team_ev ev[64];
    int n_ev = team_take_events(m, ev, 64);
    CHECK(team_count(ev, n_ev, 8 /* PEER_LOST */) == 2);
    /* AUV1 silent since 5 s: lines 1 and 2 dealt to AUV2 and AUV3 -> line 1 is AUV2's */
    const team_ev *lost = team_find(ev, n_ev, 8);
    CHECK(lost && !strcmp(lost->origin, "AUV1"));
    CHECK_HAS(lost ? lost->text : NULL, "silent");
    int taken = 0;
    for (int i = 0; i < n_ev; i++)
        if (ev[i].kind == 9 /* LINES_TAKEN */) {
            taken++;
            if (!strcmp(ev[i].origin, "AUV1"))
                CHECK(!strcmp(ev[i].text, "1"));
            else   /* AUV3 fell silent after 60 s; AUV2 is then the only survivor and
                    * takes its whole list: its own lines, then line 2 it had taken from AUV1 */
                CHECK(!strcmp(ev[i].origin, "AUV3") && !strcmp(ev[i].text, "4 5 2"));
        }
    CHECK(taken == 2);
    chasm_free(m);
}

/* A teammate that said it is done has ended its survey: the lost vehicle's
 * lines all go to the one survivor still surveying. */
void done_teammates_take_no_lines(void)
{
    chasm_machine *m = auv2_surveying();
    if (!m)
        return;
    team_msg s1 = status(0, 20, 0, 0, 1, 1, 5);   /* AUV1 flew line 0, then nothing */
    team_feed_frame(m, "AUV2", "AUV1", &s1, 1, 5);
    for (int t = 0; t <= 80; t += 20) {
        team_msg s3 = status(2, 0, 80, 0, 2, 4 /* done */, t);
        team_feed_frame(m, "AUV2", "AUV3", &s3, 1, t + 0.5);
        run(m, t == 0 ? 0.1 : t, t + 20, 0, 60);
    }
    team_ev ev[64];
    int n_ev = team_take_events(m, ev, 64);
    const team_ev *taken = team_find(ev, n_ev, 9 /* LINES_TAKEN */);
    CHECK(taken && !strcmp(taken->origin, "AUV1") && !strcmp(taken->text, "1 2"));
    chasm_free(m);
}

void aborted_teammate_is_lost_at_once(void)
{
    chasm_machine *m = surveying("me = \"AUV3\", my_slot = 2", "", 80);
    if (!m)
        return;
    team_msg s2 = status(1, 50, 60, 0, 0, 5 /* abort */, 3);
    team_feed_frame(m, "AUV3", "AUV2", &s2, 1, 3);
    run(m, 0.1, 5, 0, 80);
    team_ev ev[32];
    int n_ev = team_take_events(m, ev, 32);
    const team_ev *lost = team_find(ev, n_ev, 8);
    CHECK(lost && !strcmp(lost->origin, "AUV2") && !strcmp(lost->text, "aborted"));
    /* AUV2's one line (3) goes to the lowest-numbered survivor, AUV1 */
    CHECK(team_count(ev, n_ev, 9) == 0);
    chasm_free(m);
}

void keep_clear_gives_way_in_depth(void)
{
    chasm_machine *m =
        surveying("me = \"AUV2\", my_slot = 1", "    do keep_clear(radius = 30 m, band = 3 m, horizon = 60 s)\n", 60);
    if (!m)
        return;
    run(m, 0.1, 2, 0, 60);
    CHECK_NEAR(pt_get(m, "setpoint.depth_m"), 10, 1e-9);
    /* AUV1 100 m ahead, coming head-on: CPA 0 m in 33 s */
    team_msg s1 = status(0, 100, 60, M_PI, 0, 1, 2);
    team_feed_frame(m, "AUV2", "AUV1", &s1, 1, 2);
    run(m, 2, 3, 0, 60);
    CHECK_NEAR(pt_get(m, "setpoint.depth_m"), 13, 1e-9);
    team_ev ev[16];
    int n_ev = team_take_events(m, ev, 16);
    const team_ev *k = team_find(ev, n_ev, 10 /* KEEP_CLEAR */);
    CHECK(k && !strcmp(k->origin, "AUV1"));
    /* AUV1 turned away, 200 m off: cleared */
    team_msg s2 = status(0, 300, 60, 0, 0, 1, 4);
    team_feed_frame(m, "AUV2", "AUV1", &s2, 1, 4);
    run(m, 3, 5, 0, 60);
    CHECK_NEAR(pt_get(m, "setpoint.depth_m"), 10, 1e-9);
    /* a higher-numbered teammate close by does not make AUV2 give way */
    team_msg s3 = status(2, 10, 60, M_PI, 0, 1, 5);
    team_feed_frame(m, "AUV2", "AUV3", &s3, 1, 5);
    run(m, 5, 6, 0, 60);
    CHECK_NEAR(pt_get(m, "setpoint.depth_m"), 10, 1e-9);
    chasm_free(m);
}

void out_of_range_values_are_refused_and_logged(void)
{
    chasm_machine *m = team_load("state mission {\n"
                                 "    do team_link(" ROSTER ", me = \"AUV1\", my_slot = 0)\n"
                                 "    do search_contacts()\n"
                                 "}\n");
    if (!m)
        return;
    pt_log_clear();
    team_nav(m, 0, 0, 0, 1.5, 0);
    pt_start(m, 0);
    team_feed_contact(m, 0, 5000, 0, 0.9, 1.0);   /* beyond the schema's +-2000 m */
    team_feed_contact(m, 1, 10, 0, 0.9, 1.0);
    uint8_t junk[3] = {0xF0, 0, 0};   /* not a modem_rx_t: counted, logged */
    chasm_messages_append(m, chasm_var_find(m, "modem_rx"), junk, sizeof junk, 1000000);
    run(m, 0.1, 21, 0, 0);
    team_msg msgs[8];
    int frames;
    int n = team_take_frames(m, msgs, 8, &frames);
    CHECK(frames == 1 && n == 1 && msgs[0].id == TEAM_MSG_CONTACT && msgs[0].u.contact.number == 1);
    CHECK_HAS(pt_log, "team_link: 1 messages refused by the link codec so far");
    CHECK_HAS(pt_log, "team_link: 0 frames and 1 input messages did not decode so far");
    chasm_free(m);
}

/* An abort state with its own team_link keeps the store (the unacked contact
 * is still sent) and announces the abort in its status (code = 5). */
void abort_state_keeps_the_store_and_says_abort(void)
{
    chasm_machine *m = team_load("state mission {\n"
                                 "    do team_link(" ROSTER ", me = \"AUV1\", my_slot = 0)\n"
                                 "    do team_status() every 20 s\n"
                                 "    do search_contacts()\n"
                                 "    when elapsed > 10 s -> emergency\n"
                                 "}\n"
                                 "state emergency {\n"
                                 "    do team_link(" ROSTER ", me = \"AUV1\", my_slot = 0)\n"
                                 "    do team_status(code = 5) every 5 s\n"
                                 "}\n");
    if (!m)
        return;
    team_nav(m, 0, 0, 0, 1.5, 0);
    pt_start(m, 0);
    team_feed_contact(m, 0, 10, 10, 0.9, 1.0);
    run(m, 0.1, 21, 0, 0);
    CHECK_HAS(pt_leaf(m), "emergency");
    team_msg msgs[8];
    int frames;
    int n = team_take_frames(m, msgs, 8, &frames);
    CHECK(frames == 1 && n == 2 && msgs[0].id == TEAM_MSG_CONTACT && msgs[1].id == TEAM_MSG_STATUS);
    if (n == 2)
        CHECK(msgs[1].u.status.state == 5);
    chasm_free(m);
}
