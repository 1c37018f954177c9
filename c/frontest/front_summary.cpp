#include "frontest/front_summary.hpp"

namespace frontest {

bool to_summary(const FitResult &r, int vehicle, double mission_s, team_msg_front &out)
{
    if (r.status != Status::OK)
        return false;
    const team_front_estimate e{vehicle,          mission_s,          r.front.offset_m, r.front.angle_rad,
                                r.front.ta_c,     r.front.tb_c,       r.front.width_m,  r.sigma.offset_m,
                                r.sigma.angle_rad, r.sigma.ta_c,      r.sigma.tb_c,     r.sigma.width_m,
                                r.n};
    return team_front_summary(&e, &out) == 1;
}

Prior from_summary(const team_msg_front &m)
{
    Prior p;
    p.front.offset_m = m.offset_m;
    p.front.angle_rad = m.angle;
    p.front.ta_c = m.temp_a_c;
    p.front.tb_c = m.temp_b_c;
    p.front.width_m = m.width_m;
    p.sigma.offset_m = team_front_sigma_received("offset_m", m.offset_sigma_m);
    p.sigma.angle_rad = team_front_sigma_received("angle", m.angle_sigma);
    p.sigma.ta_c = p.sigma.tb_c = team_front_sigma_received("temp_a_c", m.temp_sigma_c);
    p.sigma.width_m = team_front_sigma_received("width_m", m.width_sigma_m);
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
