/* auv-depth's protocol: a Digiquartz-style sensor answers only when asked, so
 * the driver asks. One query is outstanding at a time:
 *
 *   opened()  *0100EW then *0100UN=n: enable the write, set the pressure unit
 *             (the answers carry no unit). The sensor echoes *0001UN=n; until
 *             that echo came, each poll slot sends UN again instead of P3.
 *   tick()    every 1/--rate s: *0100P3, one pressure. After every
 *             --temp-every pressures, a *0100Q3 right after the answer.
 *             A query unanswered for --timeout s is dropped as "no answer"
 *             and the next slot polls again.
 *   feed()    an answer for the pending query: a pressure publishes depth_t
 *             (stamped with the answer's receive time, with the newest
 *             temperature, NaN before the first), a temperature is kept.
 *
 * An answer with no query pending ("unexpected answer") cannot be told a
 * pressure from a temperature: so it is in auv-driver-replay, which replays
 * only the bytes read. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "auv/auv_depth_t.h"
#include "drivers/depth/depth.h"

#define HOST 0
#define DEFAULT_UNIT DQ_KPA
#define DEFAULT_RATE_HZ 4.0
#define DEFAULT_TEMP_EVERY 10
#define DEFAULT_TIMEOUT_S 0.5

static const char *query_name(depth_query q)
{
    return q == DEPTH_Q_UNIT ? "UN" : q == DEPTH_Q_PRESSURE ? "P3" : q == DEPTH_Q_TEMPERATURE ? "Q3" : "none";
}

static int depth_init(void *state, drv_ctx *ctx)
{
    depth_state *s = state;
    const dq_depth_model def = DQ_DEPTH_DEFAULTS;
    if (!(s->settings_done & 1))
        s->model.rho_kgpm3 = def.rho_kgpm3;
    if (!(s->settings_done & 2))
        s->model.g_mps2 = def.g_mps2;
    if (!(s->settings_done & 4))
        s->model.p_atm_pa = def.p_atm_pa;
    if (!(s->settings_done & 8))
        s->unit = DEFAULT_UNIT;
    if (!(s->settings_done & 16))
        s->address = 1;
    if (!(s->settings_done & 32))
        s->rate_hz = DEFAULT_RATE_HZ;
    if (!(s->settings_done & 64))
        s->temp_every = DEFAULT_TEMP_EVERY;
    if (!(s->settings_done & 128))
        s->timeout_s = DEFAULT_TIMEOUT_S;
    dq_framer_init(&s->framer);
    s->pending = DEPTH_Q_NONE;
    s->sent_at = s->next_poll = -1;
    s->now = -1;
    s->temperature_c = NAN;
    s->depth_type = auv_type_find("depth_t");
    if (!s->depth_type) {
        drv_log(ctx, "depth_t is not in the type table");
        return -1;
    }
    return 0;
}

/* One command line to the sensor; the query it asks is now pending. */
static void ask(depth_state *s, drv_ctx *ctx, const char *command, depth_query q)
{
    char line[DQ_MAX_LINE];
    int n = dq_format_command(line, sizeof line, s->address, HOST, command);
    if (n < 0 || drv_write(ctx, (const uint8_t *)line, (size_t)n) < 0)
        return; /* no port (replay) or a write that failed: the port's loss is the framework's */
    if (q != DEPTH_Q_NONE) {
        s->pending = q;
        s->sent_at = s->now;
    }
}

static void send_unit(depth_state *s, drv_ctx *ctx)
{
    char cmd[16];
    snprintf(cmd, sizeof cmd, "UN=%d", s->unit);
    ask(s, ctx, "EW", DEPTH_Q_NONE); /* a write command needs the enable right before it */
    ask(s, ctx, cmd, DEPTH_Q_UNIT);
}

static void depth_opened(void *state, drv_ctx *ctx)
{
    depth_state *s = state;
    s->unit_set = 0; /* the sensor may have been power-cycled with the port */
    send_unit(s, ctx);
}

static void depth_tick(void *state, drv_ctx *ctx, int64_t now)
{
    depth_state *s = state;
    s->now = now;
    if (s->pending != DEPTH_Q_NONE && s->sent_at < 0)
        s->sent_at = now;
    if (s->pending != DEPTH_Q_NONE && now - s->sent_at > (int64_t)(s->timeout_s * 1e6)) {
        drv_drop(ctx, "no answer", "%s unanswered for %.2f s", query_name(s->pending), s->timeout_s);
        s->pending = DEPTH_Q_NONE;
    }
    int64_t period = (int64_t)(1e6 / s->rate_hz);
    if (s->next_poll < 0)
        s->next_poll = now;
    if (s->pending != DEPTH_Q_NONE || now < s->next_poll)
        return;
    /* on the grid of the rate; after a stall (or a late answer), from now, no burst */
    s->next_poll += period;
    if (s->next_poll <= now)
        s->next_poll = now + period;
    if (!s->unit_set)
        send_unit(s, ctx);
    else
        ask(s, ctx, "P3", DEPTH_Q_PRESSURE);
}

static void on_pressure(depth_state *s, drv_ctx *ctx, double value, int64_t stamp)
{
    double pa;
    dq_result r = dq_pressure_pa(value, s->unit, &pa);
    if (r != DQ_OK) {
        drv_drop(ctx, dq_result_name(r), "pressure %.6g in unit %d", value, s->unit);
        return;
    }
    drv_frame_ok(ctx, stamp);
    auv_depth_t m;
    memset(&m, 0, sizeof m);
    m.utime = stamp;
    m.vehicle = (char *)ctx->vehicle;
    m.pressure_pa = pa;
    m.depth_m = dq_depth_m(&s->model, pa);
    m.temperature_c = s->temperature_c;
    m.valid = 1;
    drv_publish(ctx, "DEPTH", s->depth_type, &m);
    if (s->temp_every > 0 && ++s->polls_since_temp >= s->temp_every) {
        s->polls_since_temp = 0;
        ask(s, ctx, "Q3", DEPTH_Q_TEMPERATURE);
    }
}

static void on_answer(depth_state *s, drv_ctx *ctx, const dq_answer *a, int64_t stamp)
{
    depth_query q = s->pending;
    s->pending = DEPTH_Q_NONE;
    if (q == DEPTH_Q_PRESSURE) {
        on_pressure(s, ctx, a->value, stamp);
    } else if (q == DEPTH_Q_TEMPERATURE) {
        double c;
        dq_result r = dq_temperature_c(a->value, &c);
        if (r != DQ_OK) {
            drv_drop(ctx, dq_result_name(r), "temperature %.6g C", a->value);
            return;
        }
        drv_frame_ok(ctx, stamp);
        s->temperature_c = c;
    } else {
        /* a number where the UN echo belongs, or nothing asked: not ours to interpret */
        drv_drop(ctx, "unexpected answer", "%.6g with %s pending", a->value, query_name(q));
    }
}

/* A line the framer refused as a value: the UN echo ("*0001UN=4") is one. */
static void on_refused(depth_state *s, drv_ctx *ctx, int r, int64_t stamp)
{
    char want[16];
    snprintf(want, sizeof want, "UN=%d", s->unit);
    const char *value = s->framer.buf + 5; /* after "*ssdd": the framer keeps the line it refused */
    if (r == DQ_BAD_VALUE && s->pending == DEPTH_Q_UNIT && !strncmp(value, "UN=", 3)) {
        s->pending = DEPTH_Q_NONE;
        if (strcmp(value, want) != 0) {
            drv_drop(ctx, "unit not set", "asked %s, the sensor says %s", want, value);
            return;
        }
        drv_frame_ok(ctx, stamp);
        s->unit_set = 1;
        return;
    }
    if (r == DQ_BAD_VALUE || r == DQ_WRONG_ADDRESS || r == DQ_NOT_AN_ANSWER)
        s->pending = DEPTH_Q_NONE; /* answered, badly: not also "no answer" */
    drv_drop(ctx, dq_result_name((dq_result)r), "%.40s", s->framer.buf);
}

static void depth_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    depth_state *s = state;
    for (size_t i = 0; i < n; i++) {
        dq_answer a;
        int r = dq_framer_push(&s->framer, bytes[i], HOST, s->address, &a);
        if (r == DQ_OK)
            on_answer(s, ctx, &a, stamp);
        else if (r == DQ_OWN_COMMAND)
            ; /* our query read back on a two-wire RS-485 line: neither */
        else if (r > 0)
            on_refused(s, ctx, r, stamp);
        /* bytes outside any line: one count per run of them, not per byte */
        if (s->framer.garbage_bytes != s->garbage_seen) {
            s->garbage_seen = s->framer.garbage_bytes;
            if (!s->in_garbage)
                drv_drop(ctx, "garbage", "bytes outside any answer, from 0x%02x", bytes[i]);
            s->in_garbage = 1;
        } else if (s->framer.len > 0) {
            s->in_garbage = 0;
        }
    }
}

static void depth_reset(void *state, drv_ctx *ctx)
{
    depth_state *s = state;
    (void)ctx;
    /* a half answer of a lost stream never ends; nor does its query's answer */
    dq_framer_init(&s->framer);
    s->garbage_seen = 0;
    s->in_garbage = 0;
    s->pending = DEPTH_Q_NONE;
}

static const drv_flag depth_flags[] = {
    {"--rate", "HZ", "pressure polls per second (default 4, at most 10)", depth_set_rate},
    {"--temp-every", "N", "a temperature query after every N pressures (default 10; 0: none)",
     depth_set_temp_every},
    {"--timeout", "S", "a query unanswered after S s is counted as \"no answer\" (default 0.5)", depth_set_timeout},
    {"--units", "N", "the unit the driver sets (UN): 1 psi, 2 hPa, 3 bar, 4 kPa, 5 MPa, 6 inHg, 7 mmHg, 8 mH2O "
                     "(default 4)",
     depth_set_units},
    {"--address", "N", "the sensor's address (default 1; the host is 0)", depth_set_address},
    {"--rho", "KGPM3", "water density for depth = (p - p_atm) / (rho g) (default 1025)", depth_set_rho},
    {"--g", "MPS2", "gravity for the depth (default 9.81)", depth_set_g},
    {"--p-atm", "PA", "atmospheric pressure at the surface (default 101325)", depth_set_p_atm},
    {0},
};

const drv_protocol depth_protocol = {
    .device = "DEPTH",
    .program = "auv-depth",
    .summary = "Digiquartz-style pressure sensor, polled (*0100P3, *0100Q3; unit set with UN at start):\n"
               "one depth_t per pressure answer on <ID>.DEPTH, stamped with its receive time;\n"
               "depth = (p - p_atm) / (rho g).",
    .default_baud = 9600,
    .state_size = sizeof(depth_state),
    .flags = depth_flags,
    .init = depth_init,
    .feed = depth_feed,
    .tick = depth_tick,
    .opened = depth_opened,
    .reset = depth_reset,
};

DRV_REGISTER(depth_protocol)
