/* auv-radio: the vehicle's end of the surface radio (docs/radio.md), a driver
 * on the common framework (docs/drivers.md) whose device is a transparent
 * radio modem's byte pipe (radio_pipe.h).
 *
 * In from the radio: chunks of operator commands (radio_chunk_t in
 * radio_frame_t), assembled in a spool (radio_asm.h) and each answered with a
 * radio_ack_t; a whole whose SHA-256 matches is published on <V>.MISSION_CMD
 * or <V>.PLUGIN_UPLOAD exactly as the operator's tool encoded it (never
 * decoded: the managers' checks are the authority). Out to the radio, at the
 * surface: a radio_report_t every --report-period-s and the managers' answers
 * (<V>.MISSION_ACK). Acoustic (<V>.MODEM_RX): the shore's team-link `command`
 * issued to every manager (radio_acoustic.c). */
#ifndef RADIO_H
#define RADIO_H

#include <stdint.h>

#include "common/auth_acoustic.h"
#include "common/auth_keys.h"
#include "drivers/common/drv_protocol.h"
#include "drivers/radio/radio_asm.h"
#include "drivers/radio/radio_pipe.h"

#define RADIO_MAX_ACKS 32     /* managers' answers kept for the next surfacing */
#define RADIO_ACK_SENDS 3     /* each sent at this many reports: the radio may lose one */
#define RADIO_ACK_BYTES 1024  /* an encoded mission_ack_t (longer ones are not relayed) */
#define RADIO_COUNTERS 16     /* acoustic counters remembered: repeats run once */
#define RADIO_SHORE_INDEX 15
#define RADIO_MAX_PEERS 8     /* teammates a vehicle's status also goes to (--peers) */

typedef struct {
    uint8_t data[RADIO_ACK_BYTES];
    int len;
    int sends_left;
} radio_ack_slot;

enum { RADIO_GIVEN_TEAM = 1, RADIO_GIVEN_SURFACE = 2, RADIO_GIVEN_REPORT = 4, RADIO_GIVEN_EXPIRY = 8 };

typedef struct {
    /* flags (defaults in init for those not given) */
    int given;
    const char *spool;
    int team_index;
    double surface_depth_m, report_period_s, idle_expiry_s;
    const char *key_file;

    drv_ctx *ctx;
    rp_deframer pipe;
    ra_assembler asm_;
    int spool_open; /* 0 without --spool (replay, fuzzers): chunks are refused */
    int ready_said;
    int64_t stamp; /* of the read being fed */

    /* what the status home says */
    int have_nav;
    double lat, lon, north, east, depth;
    int32_t nav_status;
    int64_t nav_utime;
    char mission[200];
    int32_t contacts;
    radio_ack_slot acks[RADIO_MAX_ACKS];
    int n_acks;
    int64_t next_report_us;
    int32_t seq;

    /* acoustic commands */
    int32_t counters[RADIO_COUNTERS];
    int n_counters, counter_at;
    auth_keyring ring;
    int have_ring;
    auth_acoustic_window windows[AUTH_MAX_KEYS];
    int64_t last_sign_counter;
    int64_t acoustic_refused;

    /* vehicle to vehicle (radio_peers.c) */
    char peers[RADIO_MAX_PEERS][RA_ID_LEN];
    int n_peers;
    int64_t peer_reports;

    /* the summary line at exit */
    int64_t delivered, acoustic_commands, frames_dropped, frames_unsent;
} radio_state;

extern const drv_protocol radio_protocol;
extern const drv_flag radio_flags[];
extern char radio_chasm_suffix[80];

/* Frames a payload (an encoded protocol message) to the shore on the pipe; radio_send_to: to node dst. */
void radio_send(radio_state *s, const uint8_t *payload, int len, int64_t now);
void radio_send_to(radio_state *s, const char *dst, const uint8_t *payload, int len, int64_t now);
/* Vehicle to vehicle (radio_peers.c): --peers ID,ID; the status to each peer; a frame
 * from another vehicle (a peer's status, published on <V>.PEER_RADIO_REPORT, or dropped). */
int radio_peers_parse(radio_state *s, const char *list, char *err, size_t errlen);
void radio_peers_send(radio_state *s, const uint8_t *report, int len, int64_t now);
void radio_peers_heard(radio_state *s, const char *src, const uint8_t *payload, int len, int64_t now);
/* A team-link frame heard on the modem (radio_acoustic.c). */
void radio_acoustic_heard(radio_state *s, const uint8_t *frame, int len, int64_t now);
/* The key file for acoustic commands; 0 or -1 (logged). */
int radio_acoustic_init(radio_state *s);

#endif
