/* From actuators_t (rudder_rad, stern_plane_rad, prop_rpm) to the pulse
 * widths of a servo controller's channels: the channel table, its limits and
 * neutral, and the watchdog that sets neutral when the commands stop. Pure
 * logic: time is an argument, no I/O but am_config_load() reading its file.
 *
 * A channel's pulse is neutral + s * us_per_unit * value, s = -1 when the
 * channel is reversed (a servo mounted the other way), +1 otherwise, then
 * clamped to [min_us, max_us] (each clamp counted). Several channels may
 * serve one actuator (upper and lower rudder), none may serve two.
 *
 * A command is refused whole, and counted with its reason, when a value is
 * not finite (NaN, inf: no channel moves on it), or when its utime breaks the
 * project's time rule (c/common/time_policy.h: invalid, from the future,
 * out of order) or is already older than the watchdog's timeout (stale: it
 * would be applied and given up at once). The watchdog: when the newest
 * applied command is older than the timeout, or none came since the start,
 * every channel goes to its neutral, once, with the reason; the next good
 * command resumes. */
#ifndef DRIVERS_ACTUATOR_MAP_H
#define DRIVERS_ACTUATOR_MAP_H

#include <stddef.h>
#include <stdint.h>

#include "common/time_policy.h"
#include "drivers/servo/maestro.h"

typedef enum { AM_RUDDER = 0, AM_STERN_PLANE, AM_PROP, AM_N_ACTUATORS } am_actuator;

/* "rudder", "stern_plane", "prop": the names of the configuration file. */
const char *am_actuator_name(am_actuator a);

typedef struct {
    unsigned channel;     /* the controller's channel, 0..23 */
    am_actuator actuator;
    double neutral_us;    /* the pulse of a zero command, and the watchdog's */
    double us_per_unit;   /* > 0: microseconds per radian (fins) or per rpm (prop) */
    double min_us, max_us;
    int reversed;
    unsigned speed;       /* the controller's speed limit, 0 = none (maestro.h units) */
    unsigned accel;       /* its acceleration limit, 0 = none */
} am_channel;

typedef struct {
    am_channel ch[MAESTRO_MAX_CHANNELS];
    unsigned n;
    int64_t watchdog_us;      /* no fresh command for this long: neutral */
    maestro_framing framing;  /* compact, or Pololu with a device number */
} am_config;

/* Reads a channel table (docs/drivers.md, "Fins and thruster"); file names the
 * text in messages. 0, or -1 with "file:line:col: message" in err. */
int am_config_parse(am_config *cfg, const char *text, size_t len, const char *file, char *err, size_t errcap);
int am_config_load(am_config *cfg, const char *path, char *err, size_t errcap);

/* One actuators_t, the fields this driver uses. */
typedef struct {
    int64_t utime;
    double rudder_rad, stern_plane_rad, prop_rpm;
} am_command;

typedef enum {
    AM_OK = 0,
    AM_NON_FINITE,    /* a NaN or infinite value */
    AM_INVALID_TIME,  /* utime outside the valid range */
    AM_FUTURE,        /* utime more than the tolerance ahead of now */
    AM_OUT_OF_ORDER,  /* older than the newest applied command */
    AM_STALE,         /* older than the watchdog's timeout on arrival */
    AM_N_VERDICTS
} am_verdict;

const char *am_verdict_name(am_verdict v);

typedef enum {
    AM_WD_QUIET = 0,     /* nothing to do */
    AM_WD_NO_COMMAND,    /* no command since the start: neutral */
    AM_WD_TIMEOUT,       /* the newest command is older than the timeout: neutral */
} am_watchdog_event;

const char *am_watchdog_name(am_watchdog_event e);

typedef struct {
    tp_input in;              /* the newest applied command's utime */
    int at_neutral;           /* the watchdog set neutral; no command since */
    int resumed;              /* the last applied command ended a watchdog neutral */
    uint64_t applied;
    uint64_t refused[AM_N_VERDICTS];
    uint64_t clamped;         /* channel values clamped to their limits */
    uint64_t watchdog_trips;
} am_state;

void am_state_init(am_state *st);

/* The pulses of every channel of the table (targets[i] for cfg->ch[i], in
 * quarter-microseconds) for a command received at `now` (the driver's clock,
 * us). AM_OK with targets filled, or the refusal (counted, targets untouched). */
am_verdict am_apply(const am_config *cfg, am_state *st, const am_command *cmd, int64_t now, uint16_t *targets);

/* Call at every turn of the driver's loop: AM_WD_NO_COMMAND or AM_WD_TIMEOUT,
 * once, with every channel's neutral in targets; AM_WD_QUIET otherwise. */
am_watchdog_event am_watchdog(const am_config *cfg, am_state *st, int64_t now, uint16_t *targets);

/* Every channel's neutral, in quarter-microseconds. */
void am_neutral(const am_config *cfg, uint16_t *targets);

/* The bytes that set the table's channels to targets (one Set Target each:
 * every Maestro has it), and those that set each channel's speed and
 * acceleration limits at the start. Return the length written to out (at
 * least AM_MAX_OUT bytes). */
#define AM_MAX_OUT (2 * MAESTRO_MAX_CHANNELS * 6)
size_t am_encode_targets(const am_config *cfg, const uint16_t *targets, uint8_t *out);
size_t am_encode_limits(const am_config *cfg, uint8_t *out);

#endif
