/* The Micro-Modem bridge: modem_tx_t frames in, host->modem sentences out;
 * modem->host sentences in, modem_rx_t frames and modem_status_t counts out.
 * Pure logic: no LCM, no I/O, no clock of its own (every call takes the
 * vehicle's time now_us), so every exchange is a unit test. The driver process
 * owns the port and the LCM; it copies mm_rx_frame and mm_status into the LCM
 * types (same field names) and writes each out->sentence with nmea_format().
 *
 * One frame per packet, one packet at a time:
 *
 *   mm_bridge_send(frame)  -> CCCYC,0,SRC,DEST,RATE,ACK,1
 *   CADRQ,..,SRC,DEST,ACK,N,1 -> CCTXD,SRC,DEST,ACK,HEX   (the data on request)
 *   CATXD echo             -> counted sent; idle again, or waiting for CAACK
 *   CAACK from DEST        -> counted acked
 *
 * The request-then-data order (not CCTXD before the cycle, which the guide
 * also allows) because the modem's CADRQ says which frame and how many bytes
 * it takes, and because a CCTXD written early stays in the modem's buffer if
 * the cycle never starts, to leave with the next one. A frame that arrives
 * while one is on its way is refused, not queued: the simulator's modem does
 * the same (docs/modem.md), so a plan meets one behaviour in both.
 *
 * Received: CACYC from another modem (its rate) -> CARXD per frame -> CACST
 * (the SNR and the rate). A frame is held until the CACST of its packet, at
 * most rx_hold_us, then delivered: stamped with the CARXD's receive time. */
#ifndef DRIVERS_MM_BRIDGE_H
#define DRIVERS_MM_BRIDGE_H

#include <stdint.h>

#include "drivers/modem/mm_msg.h"

#define MM_TABLE_MAX 32
#define MM_NAME_MAX 32
#define MM_TEXT_MAX 128

/* Vehicle id <-> modem address: "AUV1=1,AUV2=2,SHIP=10". */
typedef struct {
    int n;
    char vehicle[MM_TABLE_MAX][MM_NAME_MAX];
    int address[MM_TABLE_MAX];
} mm_table;

/* Returns 0, or -1 with *why: an empty or malformed entry, an address outside
 * 1..127 (0 is the broadcast address), a name or an address given twice. */
int mm_table_parse(mm_table *t, const char *spec, const char **why);
int mm_table_address(const mm_table *t, const char *vehicle); /* -1 when absent */
const char *mm_table_vehicle(const mm_table *t, int address); /* NULL when absent */

typedef struct {
    const char *vehicle;      /* this vehicle; its address comes from the table */
    int rate;                 /* 0..5: every frame is sent at it */
    int ack;                  /* ask the addressee's modem to acknowledge (unicast only) */
    int kind;                 /* the modem_tx_t kind the link carries; received frames get it */
    int cst;                  /* the modem reports CACST (CCCFG,CST,1 at start): hold frames for their SNR */
    int64_t answer_timeout_us; /* CCCYC -> CADRQ, CCTXD -> CATXD */
    int64_t ack_timeout_us;    /* CATXD -> CAACK */
    int64_t rx_hold_us;        /* CARXD -> its CACST */
} mm_options;

/* rate 0, no ack, KIND_TEAM (2), cst on, 5 s, 20 s, 2 s. */
void mm_options_default(mm_options *o);

/* A frame heard: modem_rx_t's fields (the driver adds vehicle, seq). */
typedef struct {
    int64_t utime;                  /* receive time of the CARXD */
    char src_vehicle[MM_NAME_MAX];
    char dst_vehicle[MM_NAME_MAX];  /* "" for a broadcast */
    int kind;
    double snr_db;                  /* CACST snr_in; NaN without one */
    int src_address, dst_address, rate; /* rate -1 if neither CACYC nor CACST told it */
    int n_bytes;
    uint8_t payload[MM_MAX_FRAME_BYTES];
} mm_rx_frame;

/* modem_status_t's counts. */
typedef struct {
    int64_t sent, refused_size, refused_rate, refused_invalid, received, lost;
    int32_t last_refused_seq;
    char last_refusal[MM_TEXT_MAX];
    int64_t busy_until_utime;       /* 0 when idle; else when the modem is given up on */
    int64_t acked, ack_timeouts, timeouts, modem_errors, rx_dropped;
    char last_error[MM_TEXT_MAX];
    int address, rate;
    int64_t heartbeat_utime;        /* last CAREV */
    char revision[32];
} mm_status;

#define MM_OUT_SENTENCES 8
#define MM_OUT_FRAMES MM_MAX_FRAMES

/* What one call produced: sentence bodies to write, in order; frames to
 * publish; whether the status changed (publish it). */
typedef struct {
    int n_sentences;
    char sentence[MM_OUT_SENTENCES][MM_BODY_MAX];
    int n_frames;
    mm_rx_frame frame[MM_OUT_FRAMES];
    int status_changed;
} mm_out;

typedef enum { MM_IDLE, MM_WAIT_DRQ, MM_WAIT_ECHO, MM_WAIT_ACK } mm_state;

typedef struct {
    mm_options opt;
    mm_table table;
    mm_status status;
    mm_state state;
    int64_t deadline_us;
    /* the frame on its way */
    int32_t seq;
    int dest, ack;
    int n_bytes;
    uint8_t payload[MM_MAX_FRAME_BYTES];
    /* frames heard, waiting for their CACST */
    int n_held;
    mm_rx_frame held[MM_OUT_FRAMES];
    int64_t held_since_us;
    int rx_rate;                    /* from the last CACYC of another modem; -1 unknown */
} mm_bridge;

/* Checks the options against the table (the vehicle must be in it, the rate
 * known). Returns 0, or -1 with *why. */
int mm_bridge_init(mm_bridge *b, const mm_options *o, const mm_table *t, const char **why);

/* The configuration to write at start and after the modem reboots ($CAREV
 * INIT): CCCFG,SRC,<address>, CCCFG,CST,<0|1>, CCCFQ,SRC (the modem answers
 * CACFG,SRC: a different address is reported in last_error). */
void mm_bridge_start(mm_bridge *b, int64_t now_us, mm_out *out);

/* A modem_tx_t. Returns 0 when accepted (out holds the CCCYC), else 1 with the
 * refusal counted (refused_size, refused_rate: busy, refused_invalid) and
 * last_refusal set. dst_vehicle "" broadcasts. */
int mm_bridge_send(mm_bridge *b, int32_t seq, const char *dst_vehicle, int kind, const uint8_t *payload,
                   int n_bytes, int64_t now_us, mm_out *out);

/* One sentence from the modem, already parsed. */
void mm_bridge_input(mm_bridge *b, const mm_msg *m, int64_t now_us, mm_out *out);

/* Time passing: answer and ack timeouts, held frames due. Call at least a few
 * times a second. */
void mm_bridge_tick(mm_bridge *b, int64_t now_us, mm_out *out);

/* The frames still waiting for their CACST, delivered now without it (the
 * stream ended: the driver exits, a replayed log ends). */
void mm_bridge_flush(mm_bridge *b, mm_out *out);

void mm_out_clear(mm_out *out);

#endif
