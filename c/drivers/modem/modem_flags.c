/* auv-modem's own flags. Each is checked where it is read, so a bad value is
 * a usage error (exit 2) naming the flag; whether this vehicle is in the
 * table is only known after every flag (modem_protocol.c, init). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/modem/modem.h"

static int set_table(void *state, const char *v, char *err, size_t n)
{
    modem_state *s = state;
    const char *why = "";
    if (mm_table_parse(&s->table, v, &why) < 0) {
        snprintf(err, n, "--table wants VEHICLE=ADDRESS,... (addresses 1..127): %s, in '%.200s'", why, v);
        return -1;
    }
    s->have_table = 1;
    return 0;
}

static int set_rate(void *state, const char *v, char *err, size_t n)
{
    modem_state *s = state;
    char *end;
    long r = strtol(v, &end, 10);
    if (end == v || *end || mm_rate_frames((int)r) < 0 || r < 0 || r > MM_MAX_RATE) {
        snprintf(err, n, "--rate wants the Micro-Modem's rate (packet type) 0..%d, not '%s'", MM_MAX_RATE, v);
        return -1;
    }
    s->rate = (int)r;
    return 0;
}

static int set_kind(void *state, const char *v, char *err, size_t n)
{
    modem_state *s = state;
    char *end;
    long k = strtol(v, &end, 10);
    if (end == v || *end || k < 0 || k > 127) {
        snprintf(err, n, "--kind wants a modem_tx_t kind 0..127, not '%s'", v);
        return -1;
    }
    s->kind = (int)k;
    s->kind_given = 1;
    return 0;
}

static int set_ack(void *state, const char *v, char *err, size_t n)
{
    (void)v, (void)err, (void)n;
    ((modem_state *)state)->ack = 1;
    return 0;
}

static int set_no_cst(void *state, const char *v, char *err, size_t n)
{
    (void)v, (void)err, (void)n;
    ((modem_state *)state)->no_cst = 1;
    return 0;
}

/* seconds in (0, 600]: a modem that takes ten minutes to answer is gone */
static int seconds(const char *flag, const char *v, double *out, char *err, size_t n)
{
    char *end;
    double d = strtod(v, &end);
    if (end == v || *end || !isfinite(d) || d <= 0.0 || d > 600.0) {
        snprintf(err, n, "%s wants seconds in (0, 600], not '%s'", flag, v);
        return -1;
    }
    *out = d;
    return 0;
}

static int set_answer_timeout(void *state, const char *v, char *err, size_t n)
{
    return seconds("--answer-timeout", v, &((modem_state *)state)->answer_timeout_s, err, n);
}

static int set_ack_timeout(void *state, const char *v, char *err, size_t n)
{
    return seconds("--ack-timeout", v, &((modem_state *)state)->ack_timeout_s, err, n);
}

static int set_rx_hold(void *state, const char *v, char *err, size_t n)
{
    return seconds("--rx-hold", v, &((modem_state *)state)->rx_hold_s, err, n);
}

const drv_flag modem_flags[] = {
    {"--table", "ID=ADDR,...", "vehicle ids to modem addresses 1..127, the same on every vehicle (required)",
     set_table},
    {"--rate", "R", "the rate (packet type) every frame is sent at: 0 FSK 32 B, 1-2 PSK 64 B, 3-5 PSK 256 B "
                    "(default 0)",
     set_rate},
    {"--ack", NULL, "ask the addressee's modem to acknowledge each unicast frame (CAACK; default off)", set_ack},
    {"--no-cst", NULL, "do not turn on CACST (no SNR; received frames are published at once)", set_no_cst},
    {"--kind", "K", "the modem_tx_t kind the link carries; received frames get it (default 2, KIND_TEAM)",
     set_kind},
    {"--answer-timeout", "S", "no CADRQ or CATXD within S s: the cycle is given up (default 5)",
     set_answer_timeout},
    {"--ack-timeout", "S", "no CAACK within S s: counted (default 20)", set_ack_timeout},
    {"--rx-hold", "S", "a received frame waits for its CACST (SNR) at most S s (default 2)", set_rx_hold},
    {0},
};
