/* The vehicle's side of a radio transfer (docs/radio.md, "Transfers"):
 * chunks in (radio_chunk_t), a verified whole out.
 *
 * A command crosses the radio as its own encoded LCM bytes cut into numbered
 * chunks. Each partial transfer is kept in a spool folder (never where a
 * manager's loader looks), so a dive, a lost link or a restart of the gateway
 * resumes from the first chunk it lacks; the whole is handed on only when
 * every chunk is held and its SHA-256 matches. The spool's files are the
 * Python reference's (python/tools/radio/assembler.py), so either gateway
 * resumes what the other held:
 *
 *   <id>.part   the chunks' bytes, appended in order
 *   <id>.json   {"header": {"transfer_id": N, "vehicle": "...", "channel": "...",
 *                "count": N, "total_bytes": N, "sha256_hex": "..."},
 *                "next_index": N, "held": N}, written (tmp + rename) after the bytes:
 *               a restart truncates the bytes to "held"
 *   done.json   [N, ...] the last RA_DONE_KEPT finished ids, oldest first
 *
 * Bad input is refused with its reason (counted as a drop on ctx, and in
 * `refused`), and nothing is kept for it. Memory and disk are bounded: at most
 * RA_MAX_TRANSFERS partial transfers of at most RA_MAX_BYTES, the bytes on
 * disk, and a transfer idle for idle_expiry_s is dropped. */
#ifndef RADIO_ASM_H
#define RADIO_ASM_H

#include <stddef.h>
#include <stdint.h>

#include "auv/auv_radio_chunk_t.h"
#include "drivers/common/drv_ctx.h"

#define RA_MAX_BYTES (4 * 1024 * 1024) /* a plugin or a plan: the managers take plans of 256 KiB */
#define RA_MAX_CHUNK_BYTES 4096
#define RA_MAX_CHUNKS (RA_MAX_BYTES / 64) /* a sender may not cut a whole into crumbs */
#define RA_MAX_TRANSFERS 4
#define RA_DONE_KEPT 64 /* finished ids remembered: a repeated last chunk is not run twice */
#define RA_ID_LEN 64

typedef struct {
    int64_t transfer_id;
    char vehicle[RA_ID_LEN];
    char channel[16];
    int32_t count, total_bytes;
    char sha256_hex[65];
} ra_header;

typedef struct {
    int used;
    ra_header h;
    int32_t next_index;
    int64_t held_bytes;
    double last_s; /* NAN: loaded from the spool, idle from the next expiry check on */
} ra_partial;

typedef struct {
    char vehicle[RA_ID_LEN];
    char spool[512];
    double idle_expiry_s;
    ra_partial p[RA_MAX_TRANSFERS];
    uint64_t order; /* the partials' order of arrival, for the report */
    uint64_t arrived[RA_MAX_TRANSFERS];
    int64_t done[RA_DONE_KEPT];
    int n_done;
    int64_t refused; /* every refusal, for the status home */
} ra_assembler;

enum { RA_HOLDING = 0, RA_DONE = 1, RA_REFUSED = 2 }; /* radio_ack_t's states */

typedef struct {
    int32_t next_index;
    int state;
    char reason[200];
    const char *channel; /* with data: MISSION_CMD or PLUGIN_UPLOAD */
    uint8_t *data;       /* the verified whole (malloc'd: ra_offer_free), else NULL */
    size_t len;
} ra_offer;

/* Opens (creating) the spool folder and loads what it holds. 0, or -1 with
 * a message in err (the folder cannot be made). */
int ra_open(ra_assembler *a, drv_ctx *ctx, const char *vehicle, const char *spool, double idle_expiry_s, char *err,
            size_t errlen);
/* One chunk received at now_s: what to acknowledge, and the whole when complete. */
void ra_offer_chunk(ra_assembler *a, drv_ctx *ctx, const auv_radio_chunk_t *c, double now_s, ra_offer *o);
void ra_offer_free(ra_offer *o);
/* Drops the partial transfers nothing arrived for in idle_expiry_s; how many. */
int ra_expire(ra_assembler *a, drv_ctx *ctx, double now_s);
/* The partial transfers held, in order of arrival: ids and first missing indices; how many. */
int ra_holding(const ra_assembler *a, int64_t *ids, int32_t *next, int cap);

#endif
