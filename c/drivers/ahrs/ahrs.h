/* auv-ahrs: a compass or AHRS speaking NMEA 0183 HDT and PASHR, or VectorNav VNYMR (ahrs_nmea.h),
 * into ahrs_t on <VEHICLE>.AHRS (docs/drivers.md, "auv-ahrs"). */
#ifndef DRV_AHRS_H
#define DRV_AHRS_H

#include <stddef.h>
#include <stdint.h>

#include "drivers/ahrs/ahrs_nmea.h"
#include "drivers/common/drv_protocol.h"
#include "drivers/common/nmea.h"

extern const drv_protocol ahrs_protocol;

typedef struct {
    ahrs_nmea_config cfg;
    int settings_done; /* bit per flag given; the rest take AHRS_NMEA_DEFAULTS */

    nmea_framer framer;
    nmea_sentence sentence;
    uint64_t garbage_seen;
    int in_garbage;

    const auv_type_entry_t *ahrs_type;
} ahrs_state;

/* Flag setters (also for tests): --roll-sign S, --pitch-sign S (1 or -1),
 * --heading-offset DEG. */
int ahrs_set_roll_sign(void *state, const char *v, char *err, size_t n);
int ahrs_set_pitch_sign(void *state, const char *v, char *err, size_t n);
int ahrs_set_heading_offset(void *state, const char *v, char *err, size_t n);

#endif
