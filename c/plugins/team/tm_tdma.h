/* The team's medium-access schedule: time is cut into slots of slot_s
 * seconds from the global clock's zero; a round is `slots` slots; a vehicle
 * may start a frame only in its own slot, within `window` seconds of the
 * slot's start, so the frame (air time plus propagation) ends before the
 * next vehicle's slot. Integer microseconds: every vehicle computes the same
 * slot boundaries. */
#ifndef TM_TDMA_H
#define TM_TDMA_H

#include <stdint.h>

#include "plugins/lib/pu_visibility.h"

typedef struct {
    int64_t slot_us;
    int slots;
    int my_slot;
    int64_t window_us;
    int64_t last_round;   /* the round this vehicle last sent in; -1 none */
} tm_tdma;

PU_HIDDEN void tm_tdma_init(tm_tdma *t, double slot_s, int slots, int my_slot, double window_s);
/* The round number if a frame may be sent now (own slot, within the window,
 * not yet sent this round), else -1. tm_tdma_sent records it. */
PU_HIDDEN int64_t tm_tdma_may_send(const tm_tdma *t, int64_t now_us);
PU_HIDDEN void tm_tdma_sent(tm_tdma *t, int64_t round);
/* The slot in use at now (0..slots-1). */
PU_HIDDEN int tm_tdma_slot(const tm_tdma *t, int64_t now_us);

#endif
