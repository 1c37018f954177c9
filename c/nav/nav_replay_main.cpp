// auv-nav-replay: run the navigation filter over a recorded LCM log.
//
//   auv-nav-replay --config FILE.nav --log RUN.lcmlog [--vehicle AUV1] [--csv OUT.csv]
//                  [--drop SENSOR[:T0:T1]]... [--score-from T] [--lbl-csv FILE] [--timing]
//
// The same filter code as auv-nav, fed the log's sensor messages in the order
// they were recorded (so late LBL replies arrive late, as they did live),
// scored against <VEHICLE>.TRUTH at every truth sample: a CSV of estimate vs
// truth and a summary of `key value` lines on stdout. --drop ignores one
// sensor's messages (all, or those with a time of validity in [T0, T1] sim
// seconds): GPS loss, DVL dropouts. --score-from T scores only from sim time T
// (errors, NEES and distance travelled: e.g. dead reckoning from the dive). Undecodable messages are counted per
// channel and dropped. --lbl-csv writes every LBL reply's range, innovation,
// NIS and fate (accepted 1, rejected 0, not used -1). --timing adds the CPU cost of each push per sensor
// type, next to two baselines measured in the same run. Exit 0; 1 on a bad
// configuration, log or option.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

extern "C" {
#include <lcm/eventlog.h>

#include "common/lcm_rx.h"
}

#include "nav/ekf_predict.hpp"
#include "nav/nav_lcm.hpp"
#include "nav/replay_eval.hpp"

namespace {

struct Drop {
    int sensor;
    double t0, t1;
};

struct Options {
    std::string config, log, vehicle = "AUV1", csv, lbl_csv;
    std::vector<Drop> drops;
    bool timing = false;
    bool help = false;
    double score_from_s = -1e300;
};

int sensor_by_name(const std::string &s)
{
    for (int k = 0; k < nav::kSensors; k++)
        if (s == nav::sensor_name(k))
            return k;
    return -1;
}

bool parse_drop(const std::string &arg, Drop &d)
{
    const size_t colon = arg.find(':');
    d.sensor = sensor_by_name(arg.substr(0, colon));
    d.t0 = -1e300;
    d.t1 = 1e300;
    if (d.sensor < 0)
        return false;
    if (colon == std::string::npos)
        return true;
    char *end = nullptr;
    d.t0 = std::strtod(arg.c_str() + colon + 1, &end);
    if (!end || *end != ':')
        return false;
    const char *t1 = end + 1;
    d.t1 = std::strtod(t1, &end);
    return end && *end == '\0' && end != t1 && d.t1 >= d.t0;
}

bool parse_args(int argc, char **argv, Options &o)
{
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            o.help = true;
            continue;
        }
        if (a == "--timing") {
            o.timing = true;
            continue;
        }
        const char *v = i + 1 < argc ? argv[++i] : nullptr;
        Drop d;
        if (v && a == "--config") o.config = v;
        else if (v && a == "--log") o.log = v;
        else if (v && a == "--vehicle") o.vehicle = v;
        else if (v && a == "--csv") o.csv = v;
        else if (v && a == "--lbl-csv") o.lbl_csv = v;
        else if (v && a == "--score-from") {
            char *end = nullptr;
            o.score_from_s = std::strtod(v, &end);
            if (!end || *end) {
                std::fprintf(stderr, "auv-nav-replay: --score-from takes sim seconds\n");
                return false;
            }
        }
        else if (v && a == "--drop" && parse_drop(v, d)) o.drops.push_back(d);
        else {
            std::fprintf(stderr, "auv-nav-replay: bad or incomplete option '%s'%s\n", a.c_str(),
                         a == "--drop" ? " (SENSOR or SENSOR:T0:T1, sensor ahrs|depth|dvl|gps|lbl)" : "");
            return false;
        }
    }
    if (o.config.empty() || o.log.empty() || o.help) {
        std::fprintf(o.help ? stdout : stderr, "usage: auv-nav-replay --config FILE.nav --log RUN.lcmlog [--vehicle ID] [--csv OUT]\n"
                             "                      [--drop SENSOR[:T0:T1]]... [--score-from T] [--lbl-csv FILE] [--timing]\n");
        return false;
    }
    return true;
}

bool dropped(const Options &o, int sensor, int64_t utime)
{
    const double t = static_cast<double>(utime) * 1e-6;
    for (const Drop &d : o.drops)
        if (d.sensor == sensor && t >= d.t0 && t <= d.t1)
            return true;
    return false;
}

int64_t now_ns()
{
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// One decode buffer per type, reused for every event.
struct Decoder {
    const auv_type_entry_t *type;
    std::vector<unsigned char> buf;
    explicit Decoder(const char *name) : type(auv_type_find(name)), buf(type ? type->struct_size : 0) {}
};

struct Timing {
    double ns[nav::kSensors] = {};
    uint64_t n[nav::kSensors] = {};
};

// Baselines in the same run: the timer itself, and one 50 ms prediction of
// an aligned state (the part of every update that does not depend on the sensor).
void print_timing(const Timing &tm, const nav::NavFilter &f)
{
    const int reps = 20000;
    int64_t t0 = now_ns();
    volatile int64_t sink = 0;
    for (int i = 0; i < reps; i++)
        sink = sink + now_ns() - now_ns();
    const double timer_ns = static_cast<double>(now_ns() - t0) / reps / 2;
    nav::FilterState s = f.state();
    t0 = now_ns();
    for (int i = 0; i < reps; i++) {
        s.utime = f.state().utime;
        nav::predict(s, s.utime + 50000, f.config());
    }
    const double predict_ns = static_cast<double>(now_ns() - t0) / reps;
    std::printf("baseline_timer_ns %.1f\n", timer_ns);
    std::printf("baseline_predict_50ms_ns %.1f\n", predict_ns);
    for (int k = 0; k < nav::kSensors; k++)
        std::printf("cost_%s_ns %.1f\ncost_%s_count %llu\n", nav::sensor_name(k), tm.n[k] ? tm.ns[k] / static_cast<double>(tm.n[k]) : 0.0,
                    nav::sensor_name(k), (unsigned long long)tm.n[k]);
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    if (!parse_args(argc, argv, o))
        return o.help ? 0 : 1;
    nav::NavConfig cfg;
    std::vector<std::string> errors;
    if (!nav::load_config(o.config, cfg, errors)) {
        for (const std::string &e : errors)
            std::fprintf(stderr, "%s\n", e.c_str());
        return 1;
    }
    lcm_eventlog_t *log = lcm_eventlog_create(o.log.c_str(), "r");
    if (!log) {
        std::fprintf(stderr, "auv-nav-replay: cannot open log %s\n", o.log.c_str());
        return 1;
    }
    FILE *csv = nullptr;
    if (!o.csv.empty() && !(csv = std::fopen(o.csv.c_str(), "w"))) {
        std::fprintf(stderr, "auv-nav-replay: cannot write %s\n", o.csv.c_str());
        lcm_eventlog_destroy(log);
        return 1;
    }
    FILE *lbl_csv = nullptr;
    if (!o.lbl_csv.empty()) {
        if (!(lbl_csv = std::fopen(o.lbl_csv.c_str(), "w"))) {
            std::fprintf(stderr, "auv-nav-replay: cannot write %s\n", o.lbl_csv.c_str());
            lcm_eventlog_destroy(log);
            if (csv)
                std::fclose(csv);
            return 1;
        }
        std::fprintf(lbl_csv, "t_s,id,two_way_travel_s,range_m,innovation_m,nis,accepted\n");
    }
    nav::NavFilter filter(cfg);
    nav::Evaluator eval(csv, o.score_from_s);
    std::vector<Decoder> dec;
    std::map<std::string, int> channel_sensor;          // channel -> sensor index, or kSensors for truth
    for (int k = 0; k < nav::kSensors; k++) {
        dec.emplace_back(nav::kSensorChannels[k].type);
        channel_sensor[o.vehicle + "." + nav::kSensorChannels[k].topic] = k;
    }
    dec.emplace_back("ground_truth_t");
    channel_sensor[o.vehicle + ".TRUTH"] = nav::kSensors;
    dec.emplace_back("altimeter_t");
    channel_sensor[o.vehicle + ".ALTIMETER"] = nav::kSensors + 1;
    std::map<std::string, uint64_t> undecodable;
    uint64_t events = 0, used = 0, not_used = 0, skipped_truth = 0;
    Timing tm;
    nav::FilterState est;
    while (lcm_eventlog_event_t *ev = lcm_eventlog_read_next_event(log)) {
        events++;
        auto it = channel_sensor.find(ev->channel);
        if (it != channel_sensor.end()) {
            Decoder &d = dec[it->second];
            if (rx_decode(d.type, ev->data, static_cast<int>(ev->datalen), d.buf.data()) != 0) {
                undecodable[ev->channel]++;
            } else if (it->second == nav::kSensors + 1) {
                int64_t t = 0;
                const double a = nav::altimeter_reading(d.buf.data(), o.vehicle.c_str(), &t);
                if (a > 0)
                    filter.note_altitude(t, a);
                d.type->info()->decode_cleanup(d.buf.data());
            } else if (it->second == nav::kSensors) {
                const auto *tr = reinterpret_cast<const auv_ground_truth_t *>(d.buf.data());
                if (tr->utime >= filter.state().utime) {
                    filter.estimate_at(tr->utime, est);
                    eval.add(*tr, est, nav::evaluate_status(est, tr->utime, cfg), filter.altitude_at(est));
                } else {
                    skipped_truth++;    // the filter already ran past it
                }
                d.type->info()->decode_cleanup(d.buf.data());
            } else {
                nav::Measurement m;
                const auto sensor = static_cast<nav::Sensor>(it->second);
                if (nav::to_measurement(sensor, d.buf.data(), o.vehicle.c_str(), m) == nav::Convert::OK &&
                    !dropped(o, sensor, m.utime)) {
                    const int64_t t0 = o.timing ? now_ns() : 0;
                    const nav::Outcome out = filter.push(m);
                    if (lbl_csv && sensor == nav::SENSOR_LBL)
                        for (int i = 0; i < m.lbl.n; i++)
                            std::fprintf(lbl_csv, "%.6f,%d,%.7f,%.3f,%.3f,%.3f,%d\n", static_cast<double>(m.utime) * 1e-6,
                                         m.lbl.id[i], m.lbl.two_way_travel_s[i], out.reply_range_m[i],
                                         out.reply_innovation_m[i], out.reply_nis[i], out.reply_accepted[i]);
                    if (o.timing) {
                        tm.ns[sensor] += static_cast<double>(now_ns() - t0);
                        tm.n[sensor]++;
                    }
                    used++;
                } else {
                    not_used++;
                }
                d.type->info()->decode_cleanup(d.buf.data());
            }
        }
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(log);
    if (csv)
        std::fclose(csv);
    if (lbl_csv)
        std::fclose(lbl_csv);

    std::printf("events %llu\nmeasurements_used %llu\nmeasurements_not_used %llu\ntruth_skipped %llu\n",
                (unsigned long long)events, (unsigned long long)used, (unsigned long long)not_used,
                (unsigned long long)skipped_truth);
    uint64_t bad = 0;
    for (const auto &u : undecodable) {
        std::printf("undecodable %s %llu\n", u.first.c_str(), (unsigned long long)u.second);
        bad += u.second;
    }
    std::printf("undecodable_total %llu\n", (unsigned long long)bad);
    eval.print_summary(stdout);
    const nav::FilterStats &fs = filter.stats();
    std::printf("out_of_order %llu\nreplayed %llu\n", (unsigned long long)fs.out_of_order,
                (unsigned long long)fs.replayed);
    for (int k = 0; k < nav::kSensors; k++) {
        const nav::SensorStats &s = fs.sensor[k];
        std::printf("%s_accepted %llu\n%s_rejected %llu\n%s_resets %llu\n%s_too_old %llu\n", nav::sensor_name(k),
                    (unsigned long long)s.accepted, nav::sensor_name(k), (unsigned long long)s.rejected,
                    nav::sensor_name(k), (unsigned long long)s.resets, nav::sensor_name(k),
                    (unsigned long long)s.too_old);
    }
    const nav::FilterState &s = filter.state();
    std::printf("final_bias_deg %.4f\nfinal_bias_sigma_deg %.4f\n", s.x(nav::BIAS) * 180 / M_PI,
                std::sqrt(s.P(nav::BIAS, nav::BIAS)) * 180 / M_PI);
    if (o.timing)
        print_timing(tm, filter);
    return 0;
}
