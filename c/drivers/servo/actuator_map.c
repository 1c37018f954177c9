/* actuators_t to channel pulses, limits, neutral and the watchdog
 * (actuator_map.h). The table's reader is am_config.c. */
#include "drivers/servo/actuator_map.h"

#include <math.h>
#include <string.h>

const char *am_actuator_name(am_actuator a)
{
    static const char *const names[AM_N_ACTUATORS] = {"rudder", "stern_plane", "prop"};
    return (unsigned)a < AM_N_ACTUATORS ? names[a] : "?";
}

const char *am_verdict_name(am_verdict v)
{
    static const char *const names[AM_N_VERDICTS] = {"applied", "non-finite value", "invalid time",
                                                     "from the future", "out of order", "stale"};
    return (unsigned)v < AM_N_VERDICTS ? names[v] : "?";
}

const char *am_watchdog_name(am_watchdog_event e)
{
    switch (e) {
    case AM_WD_NO_COMMAND:
        return "no command since the start: neutral";
    case AM_WD_TIMEOUT:
        return "no fresh command within the watchdog timeout: neutral";
    default:
        return "quiet";
    }
}

void am_state_init(am_state *st) { memset(st, 0, sizeof *st); }

/* quarter-microseconds; the table's reader keeps every pulse within 1..4095.75 us */
static uint16_t qus(double us) { return (uint16_t)lround(us * 4.0); }

void am_neutral(const am_config *cfg, uint16_t *targets)
{
    for (unsigned i = 0; i < cfg->n; i++)
        targets[i] = qus(cfg->ch[i].neutral_us);
}

am_verdict am_apply(const am_config *cfg, am_state *st, const am_command *cmd, int64_t now, uint16_t *targets)
{
    double value[AM_N_ACTUATORS] = {cmd->rudder_rad, cmd->stern_plane_rad, cmd->prop_rpm};
    am_verdict v = AM_OK;
    /* values first: a refused message must not advance the input's newest stamp */
    for (int a = 0; a < AM_N_ACTUATORS; a++)
        if (!isfinite(value[a]))
            v = AM_NON_FINITE;
    if (v == AM_OK && tp_utime_valid(cmd->utime) && tp_sat_sub(now, cmd->utime) > cfg->watchdog_us)
        v = AM_STALE;
    if (v == AM_OK) {
        switch (tp_input_offer(&st->in, cmd->utime, 1, now, TP_FUTURE_TOLERANCE_US)) {
        case TP_OK:
            break;
        case TP_FUTURE:
            v = AM_FUTURE;
            break;
        case TP_OUT_OF_ORDER:
            v = AM_OUT_OF_ORDER;
            break;
        default:
            v = AM_INVALID_TIME;
            break;
        }
    }
    if (v != AM_OK) {
        st->refused[v]++;
        return v;
    }
    for (unsigned i = 0; i < cfg->n; i++) {
        const am_channel *c = &cfg->ch[i];
        double us = c->neutral_us + (c->reversed ? -1.0 : 1.0) * c->us_per_unit * value[c->actuator];
        if (!(us >= c->min_us) || !(us <= c->max_us)) {
            us = us < c->min_us ? c->min_us : c->max_us;
            st->clamped++;
        }
        targets[i] = qus(us);
    }
    st->resumed = st->at_neutral;
    st->at_neutral = 0;
    st->applied++;
    return AM_OK;
}

am_watchdog_event am_watchdog(const am_config *cfg, am_state *st, int64_t now, uint16_t *targets)
{
    if (st->at_neutral)
        return AM_WD_QUIET;
    am_watchdog_event e = AM_WD_QUIET;
    if (!st->in.have)
        e = AM_WD_NO_COMMAND;
    else if (tp_sat_sub(now, st->in.newest) > cfg->watchdog_us)
        e = AM_WD_TIMEOUT;
    if (e != AM_WD_QUIET) {
        am_neutral(cfg, targets);
        st->at_neutral = 1;
        st->watchdog_trips++;
    }
    return e;
}

size_t am_encode_targets(const am_config *cfg, const uint16_t *targets, uint8_t *out)
{
    size_t n = 0;
    for (unsigned i = 0; i < cfg->n; i++)
        n += maestro_set_target(&cfg->framing, out + n, cfg->ch[i].channel, targets[i]);
    return n;
}

size_t am_encode_limits(const am_config *cfg, uint8_t *out)
{
    size_t n = 0;
    for (unsigned i = 0; i < cfg->n; i++) {
        n += maestro_set_speed(&cfg->framing, out + n, cfg->ch[i].channel, cfg->ch[i].speed);
        n += maestro_set_acceleration(&cfg->framing, out + n, cfg->ch[i].channel, cfg->ch[i].accel);
    }
    return n;
}
