/* Helpers of the plan-level team tests: a plan prelude declaring the team
 * plugin's variables, hand-made modem frames fed into modem_rx, and the
 * frames and events the plan posts, decoded. */
#include <stdlib.h>

#include "auv/auv_modem_rx_t.h"
#include "auv/auv_modem_tx_t.h"
#include "auv/auv_reacquire_look_t.h"
#include "auv/auv_sidescan_contact_t.h"
#include "auv/auv_team_event_t.h"
#include "team_plan_kit.h"

const char *const TEAM_PRELUDE =
    "use team\n"
    "input  nav.north_m : double m\n"
    "input  nav.east_m : double m\n"
    "input  nav.depth_m : double m\n"
    "input  nav.heading_rad : double rad\n"
    "input  nav.speed_over_ground_mps : double m/s\n"
    "input  modem_rx : messages(256)\n"
    "input  contacts : messages(256)\n"
    "input  looks : messages\n"
    "output modem_tx : messages\n"
    "output team_events : messages(256)\n"
    "output setpoint.heading_rad : double rad\n"
    "output setpoint.vertical_mode : int\n"
    "output setpoint.depth_m : double m\n"
    "output setpoint.altitude_m : double m\n"
    "output setpoint.speed_mode : int\n"
    "output setpoint.speed_mps : double m/s\n"; /* 17 lines */

chasm_machine *team_load(const char *body)
{
    static char buf[16384];
    snprintf(buf, sizeof buf, "%s%s", TEAM_PRELUDE, body);
    return pt_load(buf);
}

const char *team_errors(const char *body)
{
    static char buf[16384];
    snprintf(buf, sizeof buf, "%s%s", TEAM_PRELUDE, body);
    return pt_errors(buf);
}

void team_nav(chasm_machine *m, double n, double e, double heading, double speed, double t)
{
    pt_set(m, "nav.north_m", n, t);
    pt_set(m, "nav.east_m", e, t);
    pt_set(m, "nav.depth_m", 5, t);
    pt_set(m, "nav.heading_rad", heading, t);
    pt_set(m, "nav.speed_over_ground_mps", speed, t);
}

static void append(chasm_machine *m, const char *var, const void *buf, int len, double t)
{
    CHECK(len > 0 && chasm_messages_append(m, chasm_var_find(m, var), buf, (size_t)len, (int64_t)(t * 1e6)) == 0);
}

void team_feed_frame(chasm_machine *m, const char *me, const char *src, const team_msg *msgs, int n, double t)
{
    uint8_t payload[256];
    team_bits w;
    team_bits_writer(&w, payload, sizeof payload);
    for (int i = 0; i < n; i++)
        CHECK(team_msg_encode(&msgs[i], &w) == TEAM_OK);
    auv_modem_rx_t f = {0};
    f.utime = (int64_t)(t * 1e6);
    f.vehicle = (char *)me;
    f.src_vehicle = (char *)src;
    f.dst_vehicle = "";
    f.kind = 2;
    f.n_bytes = (int16_t)team_bits_bytes(&w);
    f.payload = payload;
    uint8_t buf[600];
    append(m, "modem_rx", buf, auv_modem_rx_t_encode(buf, 0, sizeof buf, &f), t);
}

void team_feed_contact(chasm_machine *m, int id, double n, double e, double score, double t)
{
    auv_sidescan_contact_t k = {0};
    k.utime = (int64_t)(t * 1e6);
    k.vehicle = "AUV1";
    k.contact_id = id;
    k.north_m = n;
    k.east_m = e;
    k.position_sigma_m = 1.0;
    k.confidence = (float)score;
    k.classification = "unknown";
    uint8_t buf[400];
    append(m, "contacts", buf, auv_sidescan_contact_t_encode(buf, 0, sizeof buf, &k), t);
}

void team_feed_look(chasm_machine *m, double n, double e, int result, double t)
{
    auv_reacquire_look_t k = {0};
    k.utime = (int64_t)(t * 1e6);
    k.vehicle = "AUV4";
    k.north_m = n;
    k.east_m = e;
    k.position_sigma_m = 0.3;
    k.range_m = 3;
    k.result = (int8_t)result;
    k.confidence = 0.9f;
    uint8_t buf[400];
    append(m, "looks", buf, auv_reacquire_look_t_encode(buf, 0, sizeof buf, &k), t);
}

int team_take_frames(chasm_machine *m, team_msg *out, int max, int *frames)
{
    int n = 0;
    const void *p;
    size_t len;
    *frames = 0;
    while ((p = chasm_messages_take(m, chasm_var_find(m, "modem_tx"), &len))) {
        auv_modem_tx_t f;
        if (auv_modem_tx_t_decode(p, 0, (int)len, &f) < 0) {
            CHECK(!"a posted frame does not decode");
            continue;
        }
        CHECK(f.kind == 2 && f.n_bytes <= 32);
        (*frames)++;
        team_bits r;
        team_bits_reader(&r, f.payload, (size_t)f.n_bytes);
        team_msg msg;
        while (n < max && team_decode_next(&r, &msg) > 0)
            out[n++] = msg;
        auv_modem_tx_t_decode_cleanup(&f);
    }
    return n;
}

int team_take_events(chasm_machine *m, team_ev *out, int max)
{
    int n = 0;
    const void *p;
    size_t len;
    while ((p = chasm_messages_take(m, chasm_var_find(m, "team_events"), &len))) {
        auv_team_event_t e;
        if (auv_team_event_t_decode(p, 0, (int)len, &e) < 0) {
            CHECK(!"a posted event does not decode");
            continue;
        }
        if (n < max) {
            out[n] = (team_ev){e.kind, e.number, e.result, e.north_m, e.east_m, "", ""};
            snprintf(out[n].origin, sizeof out[n].origin, "%s", e.origin);
            snprintf(out[n].text, sizeof out[n].text, "%s", e.text);
            n++;
        }
        auv_team_event_t_decode_cleanup(&e);
    }
    return n;
}

int team_count(const team_ev *ev, int n, int kind)
{
    int c = 0;
    for (int i = 0; i < n; i++)
        c += ev[i].kind == kind;
    return c;
}

const team_ev *team_find(const team_ev *ev, int n, int kind)
{
    for (int i = 0; i < n; i++)
        if (ev[i].kind == kind)
            return &ev[i];
    return NULL;
}
