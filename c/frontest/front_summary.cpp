#include "frontest/front_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace frontest {

namespace {

const team_field_info &field(const char *name)
{
    const team_message_info *m = team_message_by_id(TEAM_MSG_FRONT);
    for (size_t i = 0; i < m->n_fields; i++)
        if (!std::strcmp(m->fields[i].name, name))
            return m->fields[i];
    return m->fields[0]; // not reached: the names are the schema's
}

// A sigma rounded up to its field's step (the codec then rounds it to itself).
double sigma_up(const char *name, double sigma)
{
    const double step = field(name).step;
    return std::ceil(sigma / step - 1e-9) * step;
}

// sigma with its parameter's quantisation (uniform over a step: variance step^2 / 12)
double with_step(const char *name, double sigma)
{
    const double step = field(name).step;
    return std::sqrt(sigma * sigma + step * step / 12);
}

}  // namespace

bool to_summary(const FitResult &r, int vehicle, double mission_s, team_msg_front &out)
{
    if (r.status != Status::OK)
        return false;
    out = team_msg_front{};
    out.vehicle = vehicle;
    out.time_s = static_cast<int32_t>(std::fmod(std::max(0.0, mission_s), 16384.0));
    out.offset_m = r.front.offset_m;
    out.angle = r.front.angle_rad;
    out.temp_a_c = r.front.ta_c;
    out.temp_b_c = r.front.tb_c;
    out.width_m = r.front.width_m;
    out.offset_sigma_m = sigma_up("offset_sigma_m", r.sigma.offset_m);
    out.angle_sigma = sigma_up("angle_sigma", r.sigma.angle_rad);
    out.temp_sigma_c = sigma_up("temp_sigma_c", std::max(r.sigma.ta_c, r.sigma.tb_c));
    out.width_sigma_m = sigma_up("width_sigma_m", r.sigma.width_m);
    out.samples = std::min(r.n, 1023);
    // the codec refuses what is out of its ranges: find out now, on a scratch frame
    uint8_t buf[TEAM_FRONT_MAX_BYTES];
    team_bits w;
    team_bits_writer(&w, buf, sizeof buf);
    return team_front_encode(&out, &w) == TEAM_OK;
}

Prior from_summary(const team_msg_front &m)
{
    Prior p;
    p.front.offset_m = m.offset_m;
    p.front.angle_rad = m.angle;
    p.front.ta_c = m.temp_a_c;
    p.front.tb_c = m.temp_b_c;
    p.front.width_m = m.width_m;
    p.sigma.offset_m = with_step("offset_m", m.offset_sigma_m);
    p.sigma.angle_rad = with_step("angle", m.angle_sigma);
    p.sigma.ta_c = p.sigma.tb_c = with_step("temp_a_c", m.temp_sigma_c);
    p.sigma.width_m = with_step("width_m", m.width_sigma_m);
    return p;
}

std::vector<team_msg_front> fronts_in_frame(const uint8_t *data, size_t len, bool *bad)
{
    std::vector<team_msg_front> out;
    team_bits r;
    team_bits_reader(&r, data, len);
    if (bad)
        *bad = false;
    for (;;) {
        team_msg m;
        const int id = team_decode_next(&r, &m);
        if (id == 0)
            break;
        if (id < 0) {
            if (bad)
                *bad = true;
            break;
        }
        if (id == TEAM_MSG_FRONT)
            out.push_back(m.u.front);
    }
    return out;
}

}  // namespace frontest
