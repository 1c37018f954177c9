/* auv-frontseat: the backseat's side of a commercial vehicle's own computer
 * (the "frontseat"), standing where the pilot stands (docs/frontseat.md).
 * It takes the navigator's <V>.SETPOINT, checks it against the vehicle's
 * limits and asks the frontseat for that heading, depth and speed in the
 * frontseat's protocol; it publishes the frontseat's navigation on <V>.NAV
 * and its state on <V>.FRONTSEAT (frontseat_status_t).
 *
 * It is a driver on the common framework (c/drivers/common): the port, the
 * flags, the clock, the raw recording, the drop counts and the status are
 * the framework's (device "FRONTSEAT": <V>.RAW.FRONTSEAT, <V>.DRIVER.FRONTSEAT).
 * What depends on the vehicle is a protocol, fs_proto: one file each
 * (iver3.c, bluefin.c), listed in fs_protocols.c. */
#ifndef FRONTSEAT_H
#define FRONTSEAT_H

#include <stddef.h>
#include <stdint.h>

#include "auv/auv_setpoint_t.h"
#include "drivers/common/drv_protocol.h"

extern const drv_protocol frontseat_protocol;

/* What the core asks a frontseat for: heading, depth, speed, already inside
 * the limits. */
typedef struct {
    double heading_deg; /* [0, 360) */
    double depth_m;     /* >= 0 */
    double speed_mps;
} fs_request;

/* The vehicle's limits (flags), and the protocol's settings they share. */
typedef struct {
    double max_depth_m;
    double min_speed_mps, max_speed_mps;
    double max_pitch_deg;     /* what the frontseat may pitch to reach a depth */
    double request_timeout_s; /* the frontseat gives control back after this without a request */
    int helm_version;         /* the frontseat software's major version (Iver3: depth units) */
} fs_limits;

/* The frontseat's navigation, from one or several of its sentences; NaN when
 * it did not say. */
typedef struct {
    double lat_deg, lon_deg;
    double depth_m, altitude_m; /* altitude < 0: unknown */
    double roll_rad, pitch_rad, heading_rad;
    double speed_mps;           /* over ground */
} fs_nav;

/* The frontseat's own state. */
typedef struct {
    char mode[16];        /* its mode word, as sent */
    int has_control;      /* the payload's requests steer it */
    int manual;           /* an operator has it */
    int error;            /* an error or abort */
    char error_text[32];  /* as sent; "" none */
} fs_report;

typedef struct fs_state fs_state;

/* One frontseat protocol: a table of functions over its own state (its
 * state_size bytes, zeroed, inside fs_state). A new vehicle is one file
 * defining one of these and one line in fs_protocols.c. */
typedef struct {
    const char *name;    /* --protocol NAME */
    const char *summary; /* for --help and docs */
    int default_baud;
    size_t state_size;
    /* Bytes from the frontseat (any bytes); whole sentences go to
     * fs_heard/fs_nav_in/fs_report_in, refusals to drv_drop. */
    void (*feed)(void *ps, fs_state *fs, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp);
    /* The request for a heading, depth and speed, written into out (size n):
     * its length, or -1. */
    int (*encode_request)(void *ps, const fs_limits *lim, const fs_request *rq, char *out, size_t n);
    /* The periodic poll for navigation and state (0: none): its length, or -1. */
    int (*encode_poll)(void *ps, char *out, size_t n);
    /* The stream broke: forget a half sentence. */
    void (*reset)(void *ps);
} fs_proto;

/* the protocols (fs_protocols.c) */
const fs_proto *fs_proto_find(const char *name);
const char *fs_proto_names(void); /* "iver3, bluefin" */
extern const fs_proto iver3_proto;
extern const fs_proto bluefin_proto;

/* ---- setpoint_t -> request (fs_setpoint.c): pure, so the tests hold it.
 * Returns NULL with *rq filled (clamped says why if something was brought
 * inside a limit), or the reason it is refused. nav_depth/nav_altitude are the
 * newest navigation (for an altitude setpoint; NaN / < 0 unknown). */
const char *fs_setpoint_request(const auv_setpoint_t *sp, const fs_limits *lim, double nav_depth_m,
                                double nav_altitude_m, fs_request *rq, char *clamped, size_t clen);

/* ---- the core (fs_core.c), called by a protocol's feed */
#define FS_PROTO_STATE_MAX 2048
struct fs_state {
    const fs_proto *proto;
    fs_limits lim;
    /* flags */
    double poll_period_s, resend_period_s, setpoint_timeout_s, silent_after_s;
    int have_origin;
    double lat0, lon0, dlat, dlon;
    int settings_done;

    /* what the frontseat said */
    int64_t last_heard;   /* -1 never */
    fs_nav nav;
    int64_t nav_stamp;    /* -1 never */
    fs_report report;
    int have_report;
    int silent;

    /* what we ask */
    auv_setpoint_t sp;    /* the newest setpoint taken (no strings kept) */
    int64_t sp_arrived;   /* -1 none */
    int have_request;
    fs_request rq;
    int64_t last_request_sent, last_poll_sent, last_status;

    /* counts for frontseat_status_t */
    int64_t setpoints_received, requests_sent, setpoints_clamped, setpoints_refused;
    int64_t control_granted, control_lost;
    char last_refusal[160];
    int8_t published_state;
    int published_control;

    _Alignas(max_align_t) unsigned char proto_state[FS_PROTO_STATE_MAX];
};

/* A whole, checked sentence of the frontseat's arrived at stamp. */
void fs_heard(fs_state *fs, drv_ctx *ctx, int64_t stamp);
/* Its navigation: fields not NaN replace the ones held; publish: a NAV now. */
void fs_nav_in(fs_state *fs, drv_ctx *ctx, const fs_nav *nav, int publish, int64_t stamp);
/* Its state report. */
void fs_report_in(fs_state *fs, drv_ctx *ctx, const fs_report *r, int64_t stamp);

#endif
