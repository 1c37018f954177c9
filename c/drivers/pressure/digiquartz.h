/* A Paroscientific Digiquartz-style pressure sensor's ASCII query and answer,
 * on RS-232 or RS-485:
 *
 *   host:   *ddssCC<CR><LF>          dd: the sensor's address (01), ss: the
 *                                    host's (00), CC: the command, e.g. P3
 *                                    "sample and send one pressure", Q3 "one
 *                                    temperature", UN=n "set the pressure unit"
 *   sensor: *ssddVALUE<CR><LF>       the answer, addressed back: *000114.7069
 *
 * Real sensors and their lines add to it, and this is accepted: spaces
 * between the address and the number, and a unit after it ("*0001 14.7069
 * psia": a number then a word of letters, which is not checked: the driver
 * set the unit); and on a two-wire RS-485 line the host reads back its own
 * commands ("*0100P3"): DQ_OWN_COMMAND, ignored.
 *
 * The answer carries a number in the sensor's configured unit (UN: 1 psi,
 * 2 hPa (mbar), 3 bar, 4 kPa, 5 MPa, 6 inHg, 7 mmHg, 8 mH2O), not the unit
 * itself: the driver sets the unit at start and converts to pascals.
 *
 * Depth from absolute pressure, stated: depth = (p - p_atm) / (rho g), with
 * rho the water's density and g the gravity, both configured (defaults: 1025
 * kg/m^3 and 9.81 m/s^2, the simulator's), and p_atm the atmosphere at the
 * surface (default 101 325 Pa; a driver can also take it from a reading at
 * the surface). A depth is a linear model of the water column: the
 * equation of state (TEOS-10) is the sampling issue's.
 *
 * No LCM, no I/O: bytes in, answers or refusal reasons out. */
#ifndef DRIVERS_DIGIQUARTZ_H
#define DRIVERS_DIGIQUARTZ_H

#include <stddef.h>
#include <stdint.h>

#define DQ_MAX_LINE 64

typedef enum {
    DQ_PSI = 1,
    DQ_HPA = 2,
    DQ_BAR = 3,
    DQ_KPA = 4,
    DQ_MPA = 5,
    DQ_INHG = 6,
    DQ_MMHG = 7,
    DQ_MH2O = 8,
} dq_unit;

/* Pascals per unit; 0 for an unknown code. */
double dq_pascals_per_unit(int unit);

typedef enum {
    DQ_OK = 0,
    DQ_NO_ANSWER_YET = -1, /* framer: nothing complete with this byte */
    DQ_TOO_LONG = 1,       /* a line over DQ_MAX_LINE */
    DQ_BAD_CHAR,           /* a byte outside printable ASCII */
    DQ_NOT_AN_ANSWER,      /* not `*` and four address digits */
    DQ_WRONG_ADDRESS,      /* addressed to another host, or from another sensor */
    DQ_BAD_VALUE,          /* not a plain decimal number */
    DQ_VALUE_RANGE,        /* a pressure below 0 or above 2000 bar; a temperature outside -10..60 C */
    DQ_OWN_COMMAND,        /* the host's own command read back (a two-wire RS-485 line
                            * echoes what the host sends): not an answer, not an error */
    DQ_RESULT_COUNT
} dq_result;

const char *dq_result_name(dq_result r);

/* The command line for one sensor address and command ("P3", "Q3", "UN=2"). */
int dq_format_command(char *out, size_t n, int sensor, int host, const char *command);

typedef struct {
    char buf[DQ_MAX_LINE + 1];
    size_t len;
    int skipping;
    uint64_t garbage_bytes; /* bytes outside a line that starts with '*' */
} dq_framer;

void dq_framer_init(dq_framer *f);

typedef struct {
    int host, sensor;
    double value; /* in the sensor's unit (pressure) or degrees C (temperature) */
} dq_answer;

/* One byte; DQ_OK with *out when an answer line ended and parsed, a refusal
 * when a line was refused, DQ_NO_ANSWER_YET otherwise. `host` and `sensor` are
 * the addresses to accept. */
int dq_framer_push(dq_framer *f, uint8_t byte, int host, int sensor, dq_answer *out);

/* A temperature answer [C], checked: -10..60 C is water a vehicle meets. */
dq_result dq_temperature_c(double value, double *c);

/* Absolute pressure [Pa] from a value in `unit`, checked (DQ_VALUE_RANGE). */
dq_result dq_pressure_pa(double value, int unit, double *pa);

typedef struct {
    double rho_kgpm3, g_mps2, p_atm_pa;
} dq_depth_model;

#define DQ_DEPTH_DEFAULTS ((dq_depth_model){.rho_kgpm3 = 1025.0, .g_mps2 = 9.81, .p_atm_pa = 101325.0})

/* Depth [m], positive down (negative above the surface: out of the water). */
double dq_depth_m(const dq_depth_model *m, double pa);

#endif
