#include "synth.hpp"

#include <algorithm>
#include <cmath>

SynthTruth Synth::truth(double t) const
{
    SynthTruth s{t, 0, 0, depth, heading, speed};
    if (turn_rate == 0) {
        s.n = speed * t * std::cos(heading);
        s.e = speed * t * std::sin(heading);
    } else {
        s.psi = heading + turn_rate * t;
        const double r = speed / turn_rate;
        s.n = r * (std::sin(s.psi) - std::sin(heading));
        s.e = r * (std::cos(heading) - std::cos(s.psi));
    }
    return s;
}

double Synth::gauss(double sigma)
{
    std::normal_distribution<double> nd(0.0, sigma);
    return nd(rng);
}

nav::Measurement Synth::lbl_ping(double t, const nav::NavConfig &cfg)
{
    nav::Measurement m{};
    m.utime = static_cast<int64_t>(std::llround(t * 1e6));
    m.sensor = nav::SENSOR_LBL;
    m.lbl.sound_speed_mps = sound_speed;
    const SynthTruth a = truth(t);
    for (int i = 0; i < cfg.n_transponders; i++) {
        const nav::Transponder &x = cfg.transponders[i];
        const double r0 = std::sqrt((x.north_m - a.n) * (x.north_m - a.n) + (x.east_m - a.e) * (x.east_m - a.e) +
                                    (x.depth_m - a.d) * (x.depth_m - a.d));
        // the reply meets the vehicle where it is when the sound is back
        double tau = 2 * r0 / sound_speed + x.turnaround_s;
        for (int k = 0; k < 3; k++) {
            const SynthTruth b = truth(t + tau);
            const double r1 = std::sqrt((x.north_m - b.n) * (x.north_m - b.n) + (x.east_m - b.e) * (x.east_m - b.e) +
                                        (x.depth_m - b.d) * (x.depth_m - b.d));
            tau = (r0 + r1) / sound_speed + x.turnaround_s;
        }
        m.lbl.id[m.lbl.n] = x.id;
        m.lbl.two_way_travel_s[m.lbl.n++] = tau + 2 * gauss(lbl_noise) / sound_speed;
    }
    return m;
}

std::vector<nav::Measurement> Synth::run(double duration_s, const nav::NavConfig &cfg)
{
    std::vector<nav::Measurement> out;
    const int steps = static_cast<int>(duration_s * 20 + 0.5);
    for (int i = 0; i <= steps; i++) {     // 20 Hz grid: AHRS every tick, depth 10 Hz, DVL 5 Hz, GPS 1 Hz
        const double t = i / 20.0;
        const SynthTruth s = truth(t);
        nav::Measurement m{};
        m.utime = static_cast<int64_t>(std::llround(t * 1e6));
        m.sensor = nav::SENSOR_AHRS;
        m.ahrs = {0, 0, std::fmod(s.psi + compass_bias + gauss(compass_noise) + 4 * M_PI, 2 * M_PI), 0, 0, turn_rate};
        out.push_back(m);
        if (i % 2 == 0) {
            m.sensor = nav::SENSOR_DEPTH;
            m.depth = {s.d + gauss(depth_noise)};
            out.push_back(m);
        }
        if (i % 4 == 0) {
            m.sensor = nav::SENSOR_DVL;
            m.dvl = {true, {s.u + gauss(dvl_noise), gauss(dvl_noise), gauss(dvl_noise)}, dvl_noise, 20.0};
            out.push_back(m);
        }
        if (i % 20 == 0 && t < gps_until_s) {
            m.sensor = nav::SENSOR_GPS;
            m.gps = {s.n + gauss(gps_noise), s.e + gauss(gps_noise), gps_noise};
            out.push_back(m);
        }
        if (lbl_period_s > 0 && i > 0 && i % static_cast<int>(std::lround(lbl_period_s * 20)) == 0)
            out.push_back(lbl_ping(t, cfg));
    }
    return out;
}

nav::NavConfig synth_config()
{
    nav::NavConfig c;
    c.transponders[0] = {1, -200, -200, 40, 0.05};
    c.transponders[1] = {2, 600, -100, 40, 0.06};
    c.transponders[2] = {3, 200, 500, 40, 0.07};
    c.n_transponders = 3;
    c.sound_speed_mps = 1500;
    c.derive();
    return c;
}
