#include "teamlink/team_front.h"

#include <math.h>
#include <string.h>

static double step_of(const char *name)
{
    const team_message_info *m = team_message_by_id(TEAM_MSG_FRONT);
    for (size_t i = 0; m && i < m->n_fields; i++)
        if (!strcmp(m->fields[i].name, name))
            return m->fields[i].step;
    return 0; /* not reached: the names are the schema's */
}

static double sigma_up(const char *name, double sigma)
{
    double step = step_of(name);
    return step > 0 ? ceil(sigma / step - 1e-9) * step : sigma;
}

int team_front_summary(const team_front_estimate *e, team_msg_front *out)
{
    memset(out, 0, sizeof *out);
    out->vehicle = e->vehicle;
    out->time_s = (int32_t)fmod(e->mission_s > 0 ? e->mission_s : 0, 16384.0);
    out->offset_m = e->offset_m;
    out->angle = e->angle_rad;
    out->temp_a_c = e->ta_c;
    out->temp_b_c = e->tb_c;
    out->width_m = e->width_m;
    out->offset_sigma_m = sigma_up("offset_sigma_m", e->offset_sigma_m);
    out->angle_sigma = sigma_up("angle_sigma", e->angle_sigma_rad);
    out->temp_sigma_c = sigma_up("temp_sigma_c", e->ta_sigma_c > e->tb_sigma_c ? e->ta_sigma_c : e->tb_sigma_c);
    out->width_sigma_m = sigma_up("width_sigma_m", e->width_sigma_m);
    out->samples = e->samples > 1023 ? 1023 : e->samples < 0 ? 0 : e->samples;
    /* the codec refuses what is out of its ranges (NaN included): find out now, on a scratch frame */
    uint8_t buf[TEAM_FRONT_MAX_BYTES];
    team_bits w;
    team_bits_writer(&w, buf, sizeof buf);
    return team_front_encode(out, &w) == TEAM_OK;
}

double team_front_sigma_received(const char *param, double sigma)
{
    double step = step_of(param);
    return sqrt(sigma * sigma + step * step / 12);
}
