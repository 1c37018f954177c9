/* A driver is a protocol and a main of a few lines (docs/drivers.md, "Writing
 * a driver"):
 *
 *     static const drv_flag gps_flags[] = {{"--origin", "LAT,LON", "...", gps_set_origin}, {0}};
 *     const drv_protocol gps_protocol = {
 *         .device = "GPS", .program = "auv-gps", .summary = "...", .default_baud = 9600,
 *         .state_size = sizeof(gps_state), .flags = gps_flags,
 *         .init = gps_init, .feed = gps_feed, .tick = gps_tick, .reset = gps_reset,
 *     };
 *     DRV_REGISTER(gps_protocol)                // auv-driver-replay and the fuzzer find it
 *
 *     int main(int argc, char **argv) { return drv_main(&gps_protocol, argc, argv); }
 *
 * The framework owns the port, LCM, the clock, the status and health
 * messages and the raw recording; the protocol only turns bytes into
 * messages through its drv_ctx (drv_publish, drv_drop, drv_frame_ok). */
#ifndef DRV_PROTOCOL_H
#define DRV_PROTOCOL_H

#include <stddef.h>
#include <stdint.h>

#include "drivers/common/drv_ctx.h"

/* One flag of the driver's own: `set` takes its value (NULL for a flag
 * without one, arg == NULL) and returns 0, or -1 with a message in err. */
typedef struct {
    const char *name; /* "--origin" */
    const char *arg;  /* "LAT,LON"; NULL: a flag without value */
    const char *help;
    int (*set)(void *state, const char *value, char *err, size_t errlen);
} drv_flag;

/* One LCM input of the driver's own (a command it passes on to the device):
 * the driver process subscribes to "<VEHICLE>.<suffix>" with the project's
 * strict typed receive (c/common/lcm_rx.h), so a message that does not decode
 * as type_name never reaches the handler: it is a drop, reason
 * "undecodable <suffix>". msg is the decoded struct (auv_<type_name>), freed
 * when the handler returns; now is the driver's clock [us]. The replay and the
 * fuzzer have no LCM input: they never call handlers. */
typedef struct {
    const char *suffix;    /* "ACTUATORS": <V>.ACTUATORS */
    const char *type_name; /* "actuators_t" (auv_type_find) */
    void (*handler)(void *state, drv_ctx *ctx, const void *msg, int64_t now);
} drv_subscription;

typedef struct drv_protocol {
    const char *device;  /* "GPS": channels <V>.RAW.GPS and <V>.DRIVER.GPS */
    const char *program; /* "auv-gps" */
    const char *summary; /* one paragraph for --help */
    int default_baud;
    size_t state_size;   /* the framework allocates it zeroed */
    const drv_flag *flags; /* ends with {0}; may be NULL */
    const drv_subscription *subscriptions; /* ends with {0}; may be NULL */
    /* Its messages carry the time the link brought (a clock, a message framed
     * whole by the simulator), not a receive stamp: the fuzzer checks that
     * they decode, not that utime is a stamp it gave. */
    int link_time;
    /* It is the vehicle's clock source (it publishes SIM.CLOCK): --clock sim,
     * which would make it follow itself, is a usage error. */
    int clock_source;

    /* Before the first byte, after the flags (state holds their values). 0 ok,
     * -1 refuses to start (with a log line). Optional. */
    int (*init)(void *state, drv_ctx *ctx);
    /* Bytes as read, all received at `stamp` (the vehicle's clock, us). Any
     * bytes at all: garbage, half frames, a frame cut between two calls. */
    void (*feed)(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp);
    /* Time passes without bytes (at least every 100 ms, and before each feed):
     * for protocols that close a frame or an epoch on silence. Optional. */
    void (*tick)(void *state, drv_ctx *ctx, int64_t now);
    /* The port opened, or opened again after a loss: send the device its
     * configuration or a first poll (drv_write). Not called by the replay,
     * whose stream has no device behind it. Optional. */
    void (*opened)(void *state, drv_ctx *ctx);
    /* The stream broke (port lost, a gap in a replayed log): forget any half
     * frame, it will never end. Optional. */
    void (*reset)(void *state, drv_ctx *ctx);
    /* The stream ended for good (exit, end of a replayed log): publish what is
     * complete. Optional. */
    void (*finish)(void *state, drv_ctx *ctx, int64_t now);
} drv_protocol;

/* Runs a driver process: flags, port, LCM, the loop; returns its exit code. */
int drv_main(const drv_protocol *p, int argc, char **argv);

/* Every linked protocol, for auv-driver-replay and the fuzzer. */
void drv_register(const drv_protocol *p);
const drv_protocol *drv_find(const char *device); /* by device name, any case */
int drv_count(void);
const drv_protocol *drv_at(int i);

#define DRV_REGISTER(proto) \
    __attribute__((constructor)) static void drv_register_##proto(void) { drv_register(&(proto)); }

#endif
