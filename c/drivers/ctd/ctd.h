/* auv-ctd: a Sea-Bird SBE 49 FastCAT (sbe49.h) into ctd_t on <VEHICLE>.CTD
 * (docs/drivers.md, "auv-ctd"). */
#ifndef DRV_CTD_H
#define DRV_CTD_H

#include <stddef.h>
#include <stdint.h>

#include "drivers/common/drv_protocol.h"
#include "drivers/ctd/sbe49.h"

extern const drv_protocol ctd_protocol;

typedef struct {
    double latitude_deg;   /* for depth from pressure */
    int configure;         /* 0: leave the instrument as it is; 1 or 3: set that OutputFormat at open */
    int settings_done;     /* bit per flag given */

    char line[SBE49_MAX_LINE + 2];
    size_t n;
    int overflow;          /* the line ran past its maximum: skip to its end */
    const auv_type_entry_t *ctd_type;
} ctd_state;

/* Flag setters (also for tests): --latitude DEG, --configure FORMAT (1 or 3). */
int ctd_set_latitude(void *state, const char *v, char *err, size_t n);
int ctd_set_configure(void *state, const char *v, char *err, size_t n);
/* One complete line (without CR LF) received at stamp: published or counted. */
void ctd_line(ctd_state *s, drv_ctx *ctx, const char *line, size_t n, int64_t stamp);

#endif
