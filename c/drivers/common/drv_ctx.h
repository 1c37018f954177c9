/* What a protocol sees of its driver: where its messages go, and where its
 * drops are counted. The same protocol code runs in the driver process (the
 * sink publishes on LCM), in auv-driver-replay (the sink publishes or prints)
 * and in the unit tests and fuzzers (the sink keeps the messages), so a
 * parser never touches LCM, a port or a clock itself. */
#ifndef DRV_CTX_H
#define DRV_CTX_H

#include <stddef.h>
#include <stdint.h>

#include "common/auv_types.h"
#include "drivers/common/drv_reasons.h"

/* An encoded message for channel (already "<VEHICLE>.<TOPIC>"). */
typedef void (*drv_sink_fn)(void *user, const char *channel, const auv_type_entry_t *type, const void *data,
                            int len);
/* Bytes to the device (a command, a poll); returns 0 when written. */
typedef int (*drv_write_fn)(void *user, const uint8_t *data, size_t n);

typedef struct drv_ctx {
    const char *program; /* "auv-gps": prefixes its log lines */
    const char *vehicle; /* "AUV1" */
    const char *device;  /* "GPS": the <DEVICE> of its RAW and DRIVER channels */
    drv_sink_fn sink;
    void *sink_user;
    drv_write_fn write;  /* NULL where there is no device (replay, tests) */
    void *write_user;
    int quiet;           /* no log lines (fuzzers, benchmarks) */

    drv_reasons reasons;
    int64_t frames_decoded;
    int64_t messages_published;
    int64_t last_frame_utime; /* -1 until a frame decoded */
    char last_error[256];
} drv_ctx;

void drv_ctx_init(drv_ctx *c, const char *program, const char *vehicle, const char *device, drv_sink_fn sink,
                  void *sink_user);

/* A frame was dropped (or bytes skipped) for `reason`; detail (printf) says
 * what, for the one log line of the first drop and for last_error. */
void drv_drop(drv_ctx *c, const char *reason, const char *detail_fmt, ...) __attribute__((format(printf, 3, 4)));

/* A whole, checked frame was decoded, received at stamp. */
void drv_frame_ok(drv_ctx *c, int64_t stamp);

/* Encodes msg (of the struct type `type`) and hands it to the sink on
 * "<VEHICLE>.<topic>". Returns 0, or -1 if it could not be encoded. */
int drv_publish(drv_ctx *c, const char *topic, const auv_type_entry_t *type, const void *msg);

/* drv_publish on a channel of the world rather than the vehicle's, as
 * given ("SIM.CLOCK": the time link's clock, which every process on the
 * vehicle's LCM follows whatever its vehicle). */
int drv_publish_global(drv_ctx *c, const char *channel, const auv_type_entry_t *type, const void *msg);

/* A message the link carried already encoded (fingerprint first), to the
 * sink on "<VEHICLE>.<topic>" as it came: the caller has decoded it as
 * `type` (rx_decode) before, so only a whole message of that type goes out. */
void drv_publish_encoded(drv_ctx *c, const char *topic, const auv_type_entry_t *type, const void *data, int len);

/* Bytes to the device through the driver's port; -1 without one. */
int drv_write(drv_ctx *c, const uint8_t *data, size_t n);

/* A log line "<program>: <DEVICE>: ..." on stderr (unless quiet). */
void drv_log(const drv_ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
