/* auv-servo's protocol: actuators_t in (a drv_subscription), Maestro commands
 * out, Get Errors replies in. The mapping, limits and watchdog are
 * actuator_map.c's, the bytes maestro.c's: this file only calls them at the
 * framework's moments, as tools/auv_maestro_encode.c does without a port. */
#include <stdio.h>
#include <string.h>

#include "auv/auv_actuators_t.h"
#include "drivers/servo/servo.h"

static int servo_set_table(void *state, const char *v, char *err, size_t n)
{
    servo_state *s = state;
    /* file:line:col from the reader itself: the driver refuses to start */
    if (am_config_load(&s->cfg, v, err, n))
        return -1;
    s->have_table = 1;
    return 0;
}

static void send_targets(servo_state *s, drv_ctx *ctx)
{
    uint8_t out[AM_MAX_OUT];
    drv_write(ctx, out, am_encode_targets(&s->cfg, s->targets, out));
}

static int servo_init(void *state, drv_ctx *ctx)
{
    servo_state *s = state;
    /* without a device (the replay, the fuzzer) there is nothing to drive,
     * and the replies decode without a table */
    if (!s->have_table && ctx->write) {
        drv_log(ctx, "--table FILE is required (the channel table, docs/drivers.md)");
        return -1;
    }
    am_state_init(&s->am);
    maestro_rx_init(&s->rx);
    am_neutral(&s->cfg, s->targets);
    return 0;
}

static void on_actuators(void *state, drv_ctx *ctx, const void *msg, int64_t now)
{
    servo_state *s = state;
    const auv_actuators_t *m = msg;
    am_command c = {m->utime, m->rudder_rad, m->stern_plane_rad, m->prop_rpm};
    uint64_t clamped = s->am.clamped;
    am_verdict v = am_apply(&s->cfg, &s->am, &c, now, s->targets);
    if (v != AM_OK) {
        drv_drop(ctx, am_verdict_name(v), "actuators_t seq %lld, utime %lld, received at %lld", (long long)m->seq,
                 (long long)m->utime, (long long)now);
        return;
    }
    drv_frame_ok(ctx, now);
    if (s->am.clamped > clamped && !s->clamp_logged) {
        s->clamp_logged = 1;
        drv_log(ctx, "actuators_t seq %lld beyond a channel's limits: clamped (further clamps are not logged)",
                (long long)m->seq);
    }
    if (s->am.resumed && !s->resume_logged) {
        s->resume_logged = 1;
        drv_log(ctx, "commands again after the watchdog: resumed (further resumptions are not logged)");
    }
    send_targets(s, ctx);
}

static void servo_opened(void *state, drv_ctx *ctx)
{
    servo_state *s = state;
    uint8_t out[AM_MAX_OUT];
    /* the baud rate indication first (a Maestro in its default serial mode
     * hears nothing before it), as a whole Get Errors whose reply is awaited */
    size_t n = maestro_baud_indication(&s->cfg.framing, out);
    if (n && drv_write(ctx, out, n) == 0) {
        maestro_rx_result r = maestro_rx_expect(&s->rx, MAESTRO_Q_ERRORS, 0);
        if (r != MRX_NONE)
            drv_drop(ctx, maestro_rx_result_name(r), "Get Errors (the baud rate indication)");
        s->baud_sent = 1;
    }
    /* a controller that was powered off lost its speed and acceleration
     * limits, and holds no target: both again */
    drv_write(ctx, out, am_encode_limits(&s->cfg, out));
    send_targets(s, ctx);
}

static void poll_errors(servo_state *s, drv_ctx *ctx, int64_t now)
{
    if (s->next_poll - now > SERVO_ERRORS_POLL_US) /* the system clock stepped back */
        s->next_poll = now;
    if (s->baud_sent) { /* that Get Errors is this period's: its reply has until the next poll */
        s->baud_sent = 0;
        s->next_poll = now + SERVO_ERRORS_POLL_US;
        return;
    }
    if (!s->have_table || now < s->next_poll)
        return;
    s->next_poll = now + SERVO_ERRORS_POLL_US;
    unsigned lost = maestro_rx_timeout(&s->rx);
    for (unsigned i = 0; i < lost; i++)
        drv_drop(ctx, maestro_rx_result_name(MRX_TIMEOUT), "no whole reply to Get Errors within %.1f s",
                 SERVO_ERRORS_POLL_US / 1e6);
    uint8_t q[MAESTRO_MAX_COMMAND];
    /* a query the port did not take is awaited by nobody */
    if (drv_write(ctx, q, maestro_get_errors(&s->cfg.framing, q)) == 0) {
        maestro_rx_result r = maestro_rx_expect(&s->rx, MAESTRO_Q_ERRORS, 0);
        if (r != MRX_NONE)
            drv_drop(ctx, maestro_rx_result_name(r), "Get Errors");
    }
}

static void servo_tick(void *state, drv_ctx *ctx, int64_t now)
{
    servo_state *s = state;
    am_watchdog_event e = am_watchdog(&s->cfg, &s->am, now, s->targets);
    if (e == AM_WD_NO_COMMAND) {
        drv_log(ctx, "%s", am_watchdog_name(e));
        send_targets(s, ctx);
    } else if (e == AM_WD_TIMEOUT) {
        /* a reason (counted, last_error) whose first is logged once */
        drv_drop(ctx, "watchdog timeout", "no fresh actuators_t within %.3f s: every channel at neutral",
                 (double)s->cfg.watchdog_us / 1e6);
        send_targets(s, ctx);
    }
    poll_errors(s, ctx, now);
}

static void on_error_bits(drv_ctx *ctx, unsigned bits)
{
    for (unsigned b = 0; b < 16; b++)
        if (bits & (1u << b))
            drv_drop(ctx, maestro_error_name(b) ? maestro_error_name(b) : "undefined error bit",
                     "the Maestro reports error bits 0x%04x", bits);
}

static void servo_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    servo_state *s = state;
    for (size_t i = 0; i < n; i++) {
        maestro_rx_event ev;
        maestro_rx_result r = maestro_rx_push(&s->rx, bytes[i], &ev);
        if (r == MRX_NONE)
            continue;
        if (r == MRX_ERRORS || r == MRX_POSITION || r == MRX_MOVING) {
            drv_frame_ok(ctx, stamp);
            if (r == MRX_ERRORS)
                on_error_bits(ctx, ev.value);
        } else {
            drv_drop(ctx, maestro_rx_result_name(r), "byte 0x%02x", bytes[i]);
        }
    }
}

static void servo_reset(void *state, drv_ctx *ctx)
{
    (void)ctx;
    servo_state *s = state;
    /* the replies to what was asked before the loss will never come */
    maestro_rx_init(&s->rx);
}

static const drv_flag servo_flags[] = {
    {"--table", "FILE", "the channel table (required): channels, limits, neutral, watchdog (docs/drivers.md)",
     servo_set_table},
    {0},
};

static const drv_subscription servo_subscriptions[] = {
    {"ACTUATORS", "actuators_t", on_actuators},
    {0},
};

const drv_protocol servo_protocol = {
    .device = "SERVO",
    .program = "auv-servo",
    .summary = "Fins and thruster on a Pololu Maestro: each actuators_t of <ID>.ACTUATORS becomes the\n"
               "channels' pulses (--table), neutral when the commands stop (the table's watchdog);\n"
               "Get Errors once a second, each error bit counted by name in <ID>.DRIVER.SERVO.",
    .default_baud = 9600,
    .state_size = sizeof(servo_state),
    .flags = servo_flags,
    .subscriptions = servo_subscriptions,
    .init = servo_init,
    .feed = servo_feed,
    .tick = servo_tick,
    .opened = servo_opened,
    .reset = servo_reset,
};

DRV_REGISTER(servo_protocol)
