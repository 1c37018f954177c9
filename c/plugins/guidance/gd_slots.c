#include "gd_slots.h"
#include "plugins/lib/pu_angle.h"

#include <stdarg.h>
#include <stdio.h>

int gd_refuse(chasm_ctx *c, const char *behavior, const char *fmt, ...)
{
    char msg[384];
    int n = snprintf(msg, sizeof msg, "%s: ", behavior);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg + n, sizeof msg - (size_t)n, fmt, ap);
    va_end(ap);
    chasm_log(c, msg);
    return -1;
}

gd_point gd_position(const chasm_ctx *c, const gd_horizontal *h)
{
    return (gd_point){chasm_read_double(c, h->in_north), chasm_read_double(c, h->in_east)};
}

void gd_command(chasm_ctx *c, const gd_horizontal *h, double heading)
{
    chasm_write_double(c, h->out_heading, pu_wrap_2pi(heading));
    chasm_write_double(c, h->out_speed, chasm_param_double(c, h->speed));
    chasm_write_int(c, h->out_speed_mode, GD_SPEED_MPS);
}
