// Nav config files: one `key value` per line, `#` comments, and one
// `transponder ID NORTH_M EAST_M DEPTH_M TURNAROUND_S` line per LBL beacon.
// Unknown keys, bad numbers and missing or extra values are all reported at
// once as file:line:col: message, with a did-you-mean for a misspelt key:
// a silently ignored key would be a silent default.
#include "nav/nav_config.hpp"

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "nav/chi2.hpp"

namespace nav {

namespace {

enum Kind { DOUBLE, INT, BOOL_FLAG_DOUBLE };

struct Key {
    const char *name;
    Kind kind;
    size_t offset;              // of the double/int member in NavConfig
    double min, max;            // accepted range (inclusive)
};

#define D(member, lo, hi) {#member, DOUBLE, offsetof(NavConfig, member), lo, hi}
#define DA(name, member, i, lo, hi) {name, DOUBLE, offsetof(NavConfig, member) + (i) * sizeof(double), lo, hi}
#define IA(name, member, i, lo, hi) {name, INT, offsetof(NavConfig, member) + (i) * sizeof(int), lo, hi}
const double BIG = 1e12;
const Key kKeys[] = {
    D(origin_latitude_deg, -90, 90),
    D(origin_longitude_deg, -180, 180),
    D(compass_noise_rad, 1e-9, 1),
    D(compass_bias_sigma_rad, 1e-9, 1),
    D(compass_bias_walk_rad_per_sqrt_s, 0, 1),
    D(gyro_noise_radps, 0, 1),
    D(attitude_noise_rad, 0, 1),
    D(depth_noise_m, 1e-6, 100),
    D(dvl_noise_mps, 1e-6, 10),
    D(dvl_water_track_extra_mps, 0, 10),
    D(dvl_water_track_surface_extra_mps, 0, 10),
    D(wave_decay_depth_m, 0.01, 1000),
    D(gps_noise_m, 1e-3, 1e4),
    D(lbl_range_noise_m, 1e-3, 1e4),
    D(accel_noise_mps2, 1e-6, 100),
    D(heave_accel_noise_mps2, 1e-6, 100),
    D(surface_zone_m, 0, 1000),
    D(surface_accel_noise_mps2, 1e-6, 100),
    D(heading_walk_rad_per_sqrt_s, 0, 10),
    D(current_walk_mps_per_sqrt_s, 0, 10),
    D(position_walk_m_per_sqrt_s, 0, 100),
    D(max_predict_step_s, 1e-4, 10),
    D(initial_velocity_sigma_mps, 1e-6, 100),
    D(initial_current_sigma_mps, 1e-6, 100),
    {"initial_north_m", BOOL_FLAG_DOUBLE, offsetof(NavConfig, initial_north_m), -BIG, BIG},
    {"initial_east_m", BOOL_FLAG_DOUBLE, offsetof(NavConfig, initial_east_m), -BIG, BIG},
    D(initial_position_sigma_m, 1e-3, 1e6),
    D(gate_probability, 0.5, 1),
    IA("reset_after_ahrs", reset_after, 0, 1, 1000000),
    IA("reset_after_depth", reset_after, 1, 1, 1000000),
    IA("reset_after_dvl", reset_after, 2, 1, 1000000),
    IA("reset_after_gps", reset_after, 3, 1, 1000000),
    IA("reset_after_lbl", reset_after, 4, 1, 1000000),
    D(degraded_sigma_m, 1e-3, BIG),
    D(invalid_sigma_m, 1e-3, BIG),
    D(degraded_heading_sigma_rad, 1e-6, 10),
    D(dvl_timeout_s, 0, BIG),
    D(input_timeout_s, 0, BIG),
    D(heading_timeout_s, 0, BIG),
    DA("aid_window_ahrs_s", aid_window_s, 0, 0, BIG),
    DA("aid_window_depth_s", aid_window_s, 1, 0, BIG),
    DA("aid_window_dvl_s", aid_window_s, 2, 0, BIG),
    DA("aid_window_gps_s", aid_window_s, 3, 0, BIG),
    DA("aid_window_lbl_s", aid_window_s, 4, 0, BIG),
    D(sound_speed_mps, 0, 2000),
    D(sound_speed_gradient_per_m, -10, 10),
    D(altitude_timeout_s, 0, 600),
    D(history_s, 0.1, 600),
};
#undef D
#undef DA
#undef IA

size_t edit_distance(const std::string &a, const std::string &b)
{
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); j++)
        row[j] = j;
    for (size_t i = 1; i <= a.size(); i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); j++) {
            size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

std::string did_you_mean(const std::string &word)
{
    const char *best = nullptr;
    size_t best_d = word.size() / 3 + 2;
    for (const Key &k : kKeys) {
        size_t d = edit_distance(word, k.name);
        if (d < best_d) {
            best_d = d;
            best = k.name;
        }
    }
    if (edit_distance(word, "transponder") < best_d)
        best = "transponder";
    return best ? std::string(" (did you mean '") + best + "'?)" : std::string();
}

struct Token {
    std::string text;
    int col;                    // 1-based
};

std::vector<Token> split(const std::string &line)
{
    std::vector<Token> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
            i++;
        if (i >= line.size() || line[i] == '#')
            break;
        size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' && line[i] != '#')
            i++;
        out.push_back({line.substr(start, i - start), static_cast<int>(start + 1)});
    }
    return out;
}

bool to_number(const std::string &s, double &out)
{
    errno = 0;
    char *end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return errno == 0 && end && *end == '\0' && end != s.c_str() && std::isfinite(out);
}

}  // namespace

const Transponder *NavConfig::transponder(int32_t id) const
{
    for (int i = 0; i < n_transponders; i++)
        if (transponders[i].id == id)
            return &transponders[i];
    return nullptr;
}

void NavConfig::derive()
{
    // gate_probability 1 switches gating off (for comparisons, not for vehicles)
    for (int k = 1; k <= 3; k++)
        gate_chi2[k] = gate_probability >= 1 ? HUGE_VAL : chi2_quantile(k, gate_probability);
}

bool parse_config(const std::string &name, const std::string &text, NavConfig &cfg,
                  std::vector<std::string> &errors)
{
    const size_t errors_before = errors.size();
    std::istringstream in(text);
    std::string line;
    int lineno = 0;
    auto err = [&](int col, const std::string &msg) {
        errors.push_back(name + ":" + std::to_string(lineno) + ":" + std::to_string(col) + ": " + msg);
    };
    while (std::getline(in, line)) {
        lineno++;
        std::vector<Token> t = split(line);
        if (t.empty())
            continue;
        const std::string &key = t[0].text;
        if (key == "transponder") {
            if (t.size() != 6) {
                err(t[0].col, "transponder needs 5 values: ID NORTH_M EAST_M DEPTH_M TURNAROUND_S");
                continue;
            }
            double v[5];
            bool ok = true;
            for (int i = 0; i < 5; i++)
                if (!to_number(t[i + 1].text, v[i])) {
                    err(t[i + 1].col, "'" + t[i + 1].text + "' is not a number");
                    ok = false;
                }
            if (!ok)
                continue;
            if (v[0] != std::floor(v[0]) || std::fabs(v[0]) > 2147483647.0) {
                err(t[1].col, "transponder id must be an integer");
                continue;
            }
            if (v[4] < 0 || v[4] > 10) {
                err(t[5].col, "turnaround must be within 0..10 s");
                continue;
            }
            if (cfg.transponder(static_cast<int32_t>(v[0]))) {
                err(t[1].col, "transponder " + t[1].text + " is defined twice");
                continue;
            }
            if (cfg.n_transponders >= kMaxTransponders) {
                err(t[0].col, "more than " + std::to_string(kMaxTransponders) + " transponders");
                continue;
            }
            cfg.transponders[cfg.n_transponders++] = {static_cast<int32_t>(v[0]), v[1], v[2], v[3], v[4]};
            continue;
        }
        const Key *k = nullptr;
        for (const Key &c : kKeys)
            if (key == c.name)
                k = &c;
        if (!k) {
            err(t[0].col, "unknown key '" + key + "'" + did_you_mean(key));
            continue;
        }
        if (t.size() != 2) {
            err(t.size() < 2 ? static_cast<int>(line.size()) + 1 : t[2].col,
                t.size() < 2 ? "'" + key + "' needs a value" : "'" + key + "' takes one value");
            continue;
        }
        double v;
        if (!to_number(t[1].text, v)) {
            err(t[1].col, "'" + t[1].text + "' is not a number");
            continue;
        }
        if (v < k->min || v > k->max) {
            std::ostringstream m;
            m << key << " = " << t[1].text << " is outside " << k->min << " .. " << k->max;
            err(t[1].col, m.str());
            continue;
        }
        char *base = reinterpret_cast<char *>(&cfg);
        if (k->kind == INT) {
            if (v != std::floor(v)) {
                err(t[1].col, "'" + key + "' must be an integer");
                continue;
            }
            *reinterpret_cast<int *>(base + k->offset) = static_cast<int>(v);
        } else {
            *reinterpret_cast<double *>(base + k->offset) = v;
            if (k->kind == BOOL_FLAG_DOUBLE)
                cfg.have_initial_position = true;
        }
    }
    if (errors.size() == errors_before && cfg.invalid_sigma_m < cfg.degraded_sigma_m)
        errors.push_back(name + ": invalid_sigma_m must be at least degraded_sigma_m");
    cfg.derive();
    return errors.size() == errors_before;
}

bool load_config(const std::string &path, NavConfig &cfg, std::vector<std::string> &errors)
{
    std::ifstream f(path);
    if (!f) {
        errors.push_back(path + ": cannot open: " + std::strerror(errno));
        return false;
    }
    std::ostringstream ss;
    ss << f.rdbuf();
    return parse_config(path, ss.str(), cfg, errors);
}

}  // namespace nav
