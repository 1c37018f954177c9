/* auv-timesync: the time link of hardware in the loop at the wire
 * (docs/drivers.md, "auv-timesync"). The simulator's time-link emulator
 * (python/sim/devices/time_link.py) writes one sentence per period:
 *
 *     $PAUVT,<sim time [us], integer>,<warp>*hh\r\n
 *
 * whose time is the sim time at which the sentence's last byte is complete at
 * this end of the line (the emulator knows the line's timing and the line
 * carries nothing else), so the time of a sentence is the time of its
 * arrival: no line delay to correct. Each sentence the project's time rule
 * accepts (c/common/time_policy.h: never backwards, a jump confirmed by a
 * second sentence) is published as SIM.CLOCK on the vehicle's LCM, which the
 * managers, auv-nav and the other drivers follow with --clock sim. */
#ifndef DRIVERS_TIMESYNC_H
#define DRIVERS_TIMESYNC_H

#include <stddef.h>
#include <stdint.h>

#include "common/time_policy.h"
#include "drivers/common/drv_protocol.h"
#include "drivers/common/nmea.h"

#define PAUVT_MAX_WARP 1e6 /* sim seconds per wall second; 0: as fast as the simulator goes */

/* One sentence's values. */
typedef struct {
    int64_t utime; /* sim time of the sentence's last byte [us] */
    double warp;   /* sim seconds per wall second */
} pauvt_values;

/* Decodes a checked sentence: NULL and *out filled, or the refusal's reason
 * ("unknown sentence", "malformed sentence", "malformed time", "time out of
 * range", "malformed warp", "warp out of range") with details in why. */
const char *pauvt_decode(const nmea_sentence *s, pauvt_values *out, char *why, size_t whylen);

/* The sentence's text for values (what the emulator writes; tests): its
 * length, or -1 if it does not fit in n. */
int pauvt_format(char *out, size_t n, int64_t utime, double warp);

typedef struct {
    nmea_framer framer;
    nmea_sentence sentence;
    uint64_t garbage_seen;
    int in_garbage;
    tp_clock clock; /* the time rule over the link's values */
    const auv_type_entry_t *clock_type;
    char server_id[64]; /* "<vehicle>-timelink" */
} timesync_state;

extern const drv_protocol timesync_protocol;

#endif
