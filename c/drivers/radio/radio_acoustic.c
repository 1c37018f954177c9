/* Acoustic commands (docs/radio.md, "Acoustic commands"): the shore's team-link
 * `command` (origin 15) addressed to this vehicle's --team-index is issued to
 * every manager as a mission_command_t, once per counter. With --key-file its
 * 32-bit tag is checked under every key of the ring, each with its own replay
 * window (c/common/auth_acoustic.h), and the command issued is signed, so a
 * manager that takes only signed commands acts on it. */
#include <stdio.h>
#include <string.h>

#include "auv/auv_mission_command_t.h"
#include "common/auth_commands.h"
#include "common/auth_verify.h"
#include "drivers/radio/radio.h"
#include "team/team_codec.h"

static const struct {
    const char *name;
    int8_t command;
} KINDS[] = {{NULL, 0}, {"abort", AUV_MISSION_COMMAND_T_CMD_ABORT}, {"pause", AUV_MISSION_COMMAND_T_CMD_PAUSE},
             {"resume", AUV_MISSION_COMMAND_T_CMD_RESUME}};

int radio_acoustic_init(radio_state *s)
{
    if (!s->key_file) {
        drv_log(s->ctx, "no --key-file: acoustic commands are not authenticated");
        return 0;
    }
    char err[256];
    if (auth_keys_load(s->key_file, &s->ring, err, sizeof err) < 0) {
        drv_log(s->ctx, "%s", err);
        return -1;
    }
    s->have_ring = 1;
    for (size_t i = 0; i < AUTH_MAX_KEYS; i++)
        auth_acoustic_init(&s->windows[i]);
    return 0;
}

static int heard_before(const radio_state *s, int32_t counter)
{
    for (int i = 0; i < s->n_counters; i++)
        if (s->counters[i] == counter)
            return 1;
    return 0;
}

/* "" if a key of the ring tags it and its counter is new, else why not. */
static const char *check_tag(radio_state *s, team_msg_command m)
{
    uint32_t tag = (uint32_t)m.mac_hi << 16 | (uint32_t)m.mac_lo;
    m.mac_hi = m.mac_lo = 0; /* the tag covers the message with a zero tag */
    uint8_t body[TEAM_COMMAND_MAX_BYTES];
    team_bits w;
    team_bits_writer(&w, body, sizeof body);
    if (team_command_encode(&m, &w) != TEAM_OK)
        return "bad_mac";
    const char *why = "bad_mac";
    for (size_t k = 0; k < s->ring.n; k++) {
        const auth_key *key = &s->ring.keys[k];
        int r = auth_acoustic_verify(&s->windows[k], key->secret, key->len, body, team_bits_bytes(&w),
                                     (uint32_t)m.counter, tag);
        if (r == 0)
            return "";
        if (r != 1)
            why = r == 2 ? "replay" : "stale"; /* this key tags it: heard before */
    }
    return why;
}

static void issue(radio_state *s, const team_msg_command *m, int64_t now)
{
    char reason[96], sender[AUTH_MAX_SENDER + 1], who[80];
    uint8_t mac[AUTH_MAC_BYTES];
    snprintf(reason, sizeof reason, "shore, acoustic %s #%d", KINDS[m->kind].name, (int)m->counter);
    auv_mission_command_t c;
    memset(&c, 0, sizeof c);
    c.utime = now;
    c.vehicle = (char *)s->ctx->vehicle;
    c.manager = "";
    c.seq = m->counter;
    c.command = KINDS[m->kind].command;
    c.plan_name = "";
    c.plan_text = "";
    c.reason = reason;
    c.auth.key_id = "";
    c.auth.sender = "";
    c.auth.mac = mac;
    if (s->have_ring) {
        int64_t counter = auth_now_us(); /* the signer's clock, strictly increasing */
        if (counter <= s->last_sign_counter)
            counter = s->last_sign_counter + 1;
        s->last_sign_counter = counter;
        snprintf(who, sizeof who, "auv-radio %s", s->ctx->vehicle);
        if (auth_sign_mission_command(&c, &s->ring.keys[s->ring.n - 1], who, counter, sender, mac) < 0) {
            drv_drop(s->ctx, "cannot sign", "acoustic %s #%d", KINDS[m->kind].name, (int)m->counter);
            return;
        }
    }
    drv_publish(s->ctx, "MISSION_CMD", auv_type_find("mission_command_t"), &c);
    s->acoustic_commands++;
}

void radio_acoustic_heard(radio_state *s, const uint8_t *frame, int len, int64_t now)
{
    team_bits r;
    team_bits_reader(&r, frame, (size_t)len);
    team_msg m;
    while (team_decode_next(&r, &m) > 0) {
        if (m.id != TEAM_MSG_COMMAND)
            continue;
        const team_msg_command *c = &m.u.command;
        if (c->origin != RADIO_SHORE_INDEX || c->target != s->team_index)
            continue; /* not the shore's, or another vehicle's */
        if (c->kind < 1 || c->kind > 3 || heard_before(s, c->counter))
            continue; /* no command we issue, or a repeat of one already run */
        if (s->have_ring) {
            const char *why = check_tag(s, *c);
            if (*why) { /* a stranger's modem, or a frame heard before */
                char reason[40];
                snprintf(reason, sizeof reason, "acoustic %s", why);
                s->acoustic_refused++;
                drv_drop(s->ctx, reason, "command #%d from the shore", (int)c->counter);
                continue;
            }
        }
        s->counters[s->counter_at] = c->counter;
        s->counter_at = (s->counter_at + 1) % RADIO_COUNTERS;
        if (s->n_counters < RADIO_COUNTERS)
            s->n_counters++;
        issue(s, c, now);
    }
}
