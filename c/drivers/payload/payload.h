/* auv-payload: the payload link of hardware in the loop at the wire
 * (docs/drivers.md, "auv-payload"). A sonar and its ATR computer stand behind
 * <V>.CONTACTS and <V>.LOOKS and have no device protocol here: the simulator
 * frames each such message whole (lcmframe.h) and this driver publishes it
 * again, byte for byte, once its frame, its topic and its type check. */
#ifndef DRIVERS_PAYLOAD_H
#define DRIVERS_PAYLOAD_H

#include <stdint.h>

#define PAYLOAD_SCRATCH 512 /* bytes: above the struct of every type in payload_topics */

#include "drivers/common/drv_protocol.h"
#include "drivers/payload/lcmframe.h"

/* The topics the link may carry and the one type each must decode as. */
typedef struct {
    const char *topic;     /* "CONTACTS": <V>.CONTACTS */
    const char *type_name; /* "sidescan_contact_t" */
} payload_topic;

extern const payload_topic payload_topics[]; /* ends with {0} */

typedef struct {
    lcmframe_framer framer;
    uint64_t garbage_seen;
    int in_garbage;
    int64_t last_byte;        /* stamp of the newest bytes; -1 before any */
    double frame_timeout_s;   /* a frame with no byte this long is cut */
    int timeout_set;
    const auv_type_entry_t *types[8]; /* payload_topics' types, in order */
    /* a decoded message, only to check it decodes: no allocation */
    _Alignas(16) uint8_t scratch[PAYLOAD_SCRATCH];
} payload_state;

extern const drv_protocol payload_protocol;

#endif
