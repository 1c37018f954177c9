/* A Sea-Bird SBE 49 FastCAT's output lines (its user's manual, "Data Output
 * Formats"), one line at a time. Each scan is a line ended by CR LF:
 *
 *   OutputFormat=1 (engineering units in hex): ttttttccccccpppppp, 18 hex
 *     digits: temperature = t / 100000 - 10 [degC, ITS-90], conductivity =
 *     c / 1000000 - 1 [S/m], pressure = p / 1000 - 100 [dbar];
 *   OutputFormat=3 (engineering units in decimal): "ttt.tttt, cc.ccccc,
 *     pppp.ppp" with ", sss.ssss" (salinity, PSU) if OutputSal=Y and
 *     ", vvvv.vvv" (sound velocity, m/s) if OutputSV=Y.
 *
 * The raw formats (0: hex counts, 2: decimal counts) need the instrument's
 * calibration coefficients and are refused with that reason. With four
 * decimal fields the fourth is a salinity or a sound velocity: they cannot
 * overlap (a sea's salinity is under 45, its sound speed over 1300 m/s). */
#ifndef DRV_SBE49_H
#define DRV_SBE49_H

#include <stddef.h>

#define SBE49_MAX_LINE 128

typedef struct {
    double temperature_c, conductivity_s_per_m, pressure_dbar;
    double salinity_psu;   /* NaN: the line had none */
    double sound_speed_mps; /* NaN: the line had none */
    int format;            /* 1 or 3 */
} sbe49_sample;

typedef enum {
    SBE49_DATA = 1,       /* *out holds a scan */
    SBE49_NOT_DATA = 0,   /* a prompt, an echo, the instrument's text: no scan, no fault */
    SBE49_BAD = -1,       /* a scan that fails its format or its ranges: *why says which */
} sbe49_kind;

/* One line without its CR LF (a prompt "S>" in front is skipped). */
sbe49_kind sbe49_parse_line(const char *line, size_t n, sbe49_sample *out, const char **why);

#endif
