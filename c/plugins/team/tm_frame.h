/* Between the store and the team-link codec (build/gen/team/team_codec.h):
 * a frame writer for tm_outbox_fill that encodes items from the store, and a
 * reader that applies a received frame to the store. */
#ifndef TM_FRAME_H
#define TM_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "tm_store.h"

/* Fills buf (cap bytes) with one frame; *n_put/put receive the items sent.
 * Returns the frame's length in bytes (0: nothing to send). */
PU_HIDDEN size_t tm_frame_build(tm_store *s, int64_t now_us, uint8_t *buf, size_t cap, tm_item *put, int max_put,
                                int *n_put);
/* Applies a frame heard from team member src. Returns the number of
 * messages decoded, or -1 if part of the frame was undecodable (counted). */
PU_HIDDEN int tm_frame_receive(tm_store *s, int src, const uint8_t *buf, size_t len, int64_t now_us);
/* Mission time [s] of a 14-bit time_s stamp heard at now (the newest such time not after now). */
PU_HIDDEN double tm_time_unwrap(int time_s, double now_s);

#endif
