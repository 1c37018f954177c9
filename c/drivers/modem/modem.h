/* auv-modem: the WHOI Micro-Modem driver (docs/drivers.md, "auv-modem"). The
 * bridge (mm_bridge.h) does the protocol; this is its wrapper on the driver
 * framework: modem_tx_t of <V>.MODEM_TX in (a drv_subscription), the modem's
 * sentences in through the NMEA framer, <V>.MODEM_RX and <V>.MODEM_STATUS
 * out, as the simulator's modem publishes them (docs/modem.md), so a team
 * plan runs unchanged on a real modem. Device name MODEM. */
#ifndef DRV_MODEM_H
#define DRV_MODEM_H

#include <stdint.h>

#include "common/auv_types.h"
#include "drivers/common/drv_protocol.h"
#include "drivers/modem/mm_bridge.h"

/* MODEM_STATUS at least this often, and whenever a count changes */
#define MODEM_STATUS_PERIOD_US INT64_C(1000000)

typedef struct {
    /* the flags (the state starts zeroed: 0 means "not given") */
    int have_table;
    mm_table table;
    int rate, ack, no_cst, kind, kind_given;
    double answer_timeout_s, ack_timeout_s, rx_hold_s;

    mm_bridge bridge;
    nmea_framer framer;
    nmea_sentence sentence;
    uint64_t garbage_seen;
    int in_garbage;
    mm_out out;              /* what the last bridge call produced */
    mm_status counted;       /* the bridge's counts already turned into drops */
    const auv_type_entry_t *rx_type, *status_type;
    int64_t next_status;     /* the driver's clock [us]; 0: at the first tick */
    int32_t rx_seq;          /* frames published on MODEM_RX (the modem does not carry the sender's seq) */
} modem_state;

extern const drv_protocol modem_protocol;

/* The flags (modem_flags.c). */
extern const drv_flag modem_flags[];

#endif
