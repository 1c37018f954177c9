/* Vehicle to vehicle (docs/radio.md, "Vehicle to vehicle"): with --peers, each
 * status home also goes to every teammate listed, and a teammate's status heard
 * over the radio is published on <V>.PEER_RADIO_REPORT (radio_report_t, as it
 * came). Nothing else is taken from another vehicle: commands come from the
 * shore only, so a frame of another kind from a vehicle is dropped. */
#include <stdio.h>
#include <string.h>

#include "auv/auv_radio_report_t.h"
#include "common/lcm_rx.h"
#include "drivers/radio/radio.h"

int radio_peers_parse(radio_state *s, const char *list, char *err, size_t errlen)
{
    s->n_peers = 0;
    for (const char *p = list; *p;) {
        size_t n = strcspn(p, ",");
        if (n == 0 || n >= RA_ID_LEN || s->n_peers == RADIO_MAX_PEERS || !strncmp(p, "SHORE", n)) {
            snprintf(err, errlen, "--peers: '%s': at most %d vehicle ids, comma-separated", list, RADIO_MAX_PEERS);
            return -1;
        }
        memcpy(s->peers[s->n_peers], p, n);
        s->peers[s->n_peers++][n] = '\0';
        p += n + (p[n] == ',');
    }
    return 0;
}

void radio_peers_send(radio_state *s, const uint8_t *report, int len, int64_t now)
{
    for (int i = 0; i < s->n_peers; i++)
        if (strcmp(s->peers[i], s->ctx->vehicle))
            radio_send_to(s, s->peers[i], report, len, now);
}

static int is_peer(const radio_state *s, const char *id)
{
    for (int i = 0; i < s->n_peers; i++)
        if (!strcmp(s->peers[i], id))
            return 1;
    return 0;
}

void radio_peers_heard(radio_state *s, const char *src, const uint8_t *payload, int len, int64_t now)
{
    const auv_type_entry_t *type = auv_type_find("radio_report_t");
    auv_radio_report_t r;
    if (!is_peer(s, src)) {
        s->frames_dropped++;
        drv_drop(s->ctx, "not a peer", "a frame from %.32s", src);
        return;
    }
    if (rx_decode(type, payload, len, &r) != 0) {
        s->frames_dropped++;
        drv_drop(s->ctx, "not a peer's status", "a frame from %.32s", src);
        return;
    }
    int own = !strcmp(r.vehicle, src);
    auv_radio_report_t_decode_cleanup(&r);
    if (!own) { /* a teammate speaks for itself only */
        s->frames_dropped++;
        drv_drop(s->ctx, "another vehicle's status", "from %.32s", src);
        return;
    }
    drv_frame_ok(s->ctx, now);
    drv_publish_encoded(s->ctx, "PEER_RADIO_REPORT", type, payload, len);
    s->peer_reports++;
}
