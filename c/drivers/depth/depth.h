/* auv-depth: a Digiquartz-style pressure sensor (c/drivers/pressure/digiquartz.h)
 * polled for pressure and temperature, into depth_t on <VEHICLE>.DEPTH
 * (docs/drivers.md, "auv-depth"). */
#ifndef DRV_DEPTH_H
#define DRV_DEPTH_H

#include <stddef.h>
#include <stdint.h>

#include "drivers/common/drv_protocol.h"
#include "drivers/pressure/digiquartz.h"

extern const drv_protocol depth_protocol;

/* The one query the driver waits for an answer to. */
typedef enum { DEPTH_Q_NONE = 0, DEPTH_Q_UNIT, DEPTH_Q_PRESSURE, DEPTH_Q_TEMPERATURE } depth_query;

typedef struct {
    /* settings (flags) */
    dq_depth_model model;
    int unit;           /* UN code, dq_unit */
    int address;        /* the sensor's; the host is 00 */
    double rate_hz;
    int temp_every;     /* a Q3 after every N-th pressure; 0: never */
    double timeout_s;   /* a query unanswered this long is "no answer" */
    int settings_done;

    dq_framer framer;
    uint64_t garbage_seen;
    int in_garbage;

    int unit_set;       /* the sensor echoed our UN */
    depth_query pending;
    int64_t sent_at;    /* -1: sent from opened(), which has no clock; timed from the next tick */
    int64_t now;        /* the newest tick */
    int64_t next_poll;  /* -1: poll at the next tick */
    int polls_since_temp;
    double temperature_c; /* NaN until a Q3 was answered */
    const auv_type_entry_t *depth_type;
} depth_state;

/* Flag setters (also for tests). */
int depth_set_rho(void *state, const char *v, char *err, size_t n);
int depth_set_g(void *state, const char *v, char *err, size_t n);
int depth_set_p_atm(void *state, const char *v, char *err, size_t n);
int depth_set_units(void *state, const char *v, char *err, size_t n);
int depth_set_address(void *state, const char *v, char *err, size_t n);
int depth_set_rate(void *state, const char *v, char *err, size_t n);
int depth_set_temp_every(void *state, const char *v, char *err, size_t n);
int depth_set_timeout(void *state, const char *v, char *err, size_t n);

#endif
