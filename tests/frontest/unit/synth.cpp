#include "synth.hpp"

#include <cmath>

namespace synth {

double Noise::gauss()
{
    const double u1 = uniform(), u2 = uniform();
    return std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

std::vector<frontest::Sample> zigzag(const frontest::Front &f, double s0, double length, double reach,
                                     double leg_angle, double step, double sigma_c, uint32_t seed)
{
    Noise noise(seed);
    const frontest::Vec q = frontest::to_q(f);
    const double c = std::cos(f.angle_rad), sn = std::sin(f.angle_rad);
    std::vector<frontest::Sample> out;
    // in the front's frame: s along, r across; legs between r = offset - reach and offset + reach
    double s = s0, r = f.offset_m - reach, dir = 1;
    const double ds = step * std::cos(leg_angle), dr = step * std::sin(leg_angle);
    int64_t t = 0;
    while (s < s0 + length) {
        const double n = s * c - r * sn, e = s * sn + r * c;
        frontest::Sample x;
        x.north_m = n;
        x.east_m = e;
        x.temperature_c = frontest::model(q, n, e) + sigma_c * noise.gauss();
        x.utime = t;
        out.push_back(x);
        t += 1000000;
        s += ds;
        r += dir * dr;
        if (r > f.offset_m + reach || r < f.offset_m - reach)
            dir = -dir;
    }
    return out;
}

}  // namespace synth
