/* The command line every driver shares, and the hook for each driver's own
 * flags (drv_protocol.flags):
 *
 *   --device PATH --baud N | --tcp HOST:PORT   the port (exactly one)
 *   --vehicle ID                                its channels' prefix (required)
 *   --lcm-url URL                               (--url is the old spelling)
 *   --raw                                       publish the bytes on <V>.RAW.<DEVICE>
 *   --clock system|sim                          the clock of the stamps
 *   --help */
#ifndef DRV_OPTIONS_H
#define DRV_OPTIONS_H

#include <stdio.h>

#include "drivers/common/drv_protocol.h"

typedef enum { DRV_CLOCK_SYSTEM, DRV_CLOCK_SIM } drv_clock_mode;

typedef struct {
    const char *device_path;
    int baud;
    const char *tcp;
    const char *vehicle;
    const char *lcm_url;
    int raw;
    drv_clock_mode clock;
} drv_options;

/* 0: parsed; 1: --help was printed (exit 0); 2: a usage error was printed on
 * stderr (exit 2). `state` receives the driver's own flags. */
int drv_options_parse(drv_options *o, const drv_protocol *p, void *state, int argc, char **argv);

void drv_options_usage(FILE *out, const drv_protocol *p);

#endif
