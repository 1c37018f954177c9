// auv-nav: the vehicle's onboard navigation filter as a process.
//
//   auv-nav --config FILE.nav [--vehicle AUV1] [--channel AUV1.NAV] [--status-channel AUV1.NAV_STATUS]
//           [--rate 20] [--clock sim|system] [--lcm-url URL] [--check]
//
// Reads <VEHICLE>.AHRS, .DEPTH, .DVL, .GPS and .LBL; publishes
// nav_solution_t (source SOURCE_EKF) on --channel at --rate Hz on the mission
// clock once aligned, and nav_filter_status_t plus process_health_t once a
// second. --clock sim follows SIM.CLOCK (nothing is published until it
// ticks), --clock system the host clock (a real vehicle). SIGINT/SIGTERM end
// it cleanly (exit 0). Exit 1: bad configuration; 2: usage or LCM failure.
// --check only reads the configuration: "ok" and exit 0, or its errors and 1.
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "nav/nav_node.hpp"

namespace {

volatile sig_atomic_t g_stop = 0;

void on_signal(int) { g_stop = 1; }

void usage(FILE *out = stderr)
{
    std::fprintf(out, "usage: auv-nav --config FILE.nav [--vehicle ID] [--channel CH] [--status-channel CH]\n"
                      "               [--rate HZ] [--clock sim|system] [--lcm-url URL] [--check]\n"
                      "               [--future-tolerance S] [--max-clock-jump S]\n"
                      "  --lcm-url URL         LCM URL (default: $LCM_DEFAULT_URL, else liblcm's default);\n"
                      "                        --url is the old spelling of it\n"
                      "  --future-tolerance S  drop sensor messages stamped more than S ahead of the clock (default 1)\n"
                      "  --max-clock-jump S    a clock jump over S needs a second message to confirm it (default 60)\n");
}

bool seconds_arg(const char *opt, const char *v, double lo, double hi, int64_t &out_us)
{
    char *end = nullptr;
    const double x = std::strtod(v, &end);
    if (!end || end == v || *end || !(x >= lo && x <= hi)) {
        std::fprintf(stderr, "auv-nav: %s wants seconds from %g to %g, not '%s'\n", opt, lo, hi, v);
        return false;
    }
    out_us = static_cast<int64_t>(x * 1e6);
    return true;
}

bool parse_args(int argc, char **argv, nav::NodeOptions &o, bool &check)
{
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i];
        if (a == "--check") {
            check = true;
            continue;
        }
        if (a == "--help" || a == "-h") {
            usage(stdout);
            std::exit(0);
        }
        const char *v = i + 1 < argc ? argv[i + 1] : nullptr;
        if (!v) {
            std::fprintf(stderr, "auv-nav: bad or incomplete option '%s'\n", a.c_str());
            return false;
        }
        if (a == "--config") o.config_path = v;
        else if (a == "--vehicle") o.vehicle = v;
        else if (a == "--channel") o.channel = v;
        else if (a == "--status-channel") o.status_channel = v;
        else if (a == "--lcm-url" || a == "--url") o.url = v;
        else if (a == "--future-tolerance") {
            if (!seconds_arg("--future-tolerance", v, 0, 3600, o.future_tol_us))
                return false;
        } else if (a == "--max-clock-jump") {
            if (!seconds_arg("--max-clock-jump", v, 1e-3, 86400, o.max_clock_jump_us))
                return false;
        }
        else if (a == "--rate") {
            char *end = nullptr;
            o.rate_hz = std::strtod(v, &end);
            if (!end || *end || !(o.rate_hz > 0 && o.rate_hz <= 1000)) {
                std::fprintf(stderr, "auv-nav: --rate must be a number in (0, 1000]\n");
                return false;
            }
        } else if (a == "--clock" && (!std::strcmp(v, "sim") || !std::strcmp(v, "system")))
            o.sim_clock = !std::strcmp(v, "sim");
        else {
            std::fprintf(stderr, "auv-nav: bad or incomplete option '%s'\n", a.c_str());
            return false;
        }
        i++;
    }
    if (o.config_path.empty() || o.vehicle.empty()) {
        usage();
        return false;
    }
    return true;
}

int64_t system_now_us()
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return static_cast<int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

int run(nav::NavNode &node, lcm_t *lcm, const nav::NodeOptions &o)
{
    const int64_t period_us = static_cast<int64_t>(1e6 / o.rate_hz);
    int64_t next_cycle = 0;
    while (!g_stop) {
        node.lockstep_poll();
        int wait_ms = 20;
        if (!o.sim_clock) {
            node.set_now(system_now_us());
            if (next_cycle > node.now())
                wait_ms = static_cast<int>(std::min<int64_t>((next_cycle - node.now()) / 1000, 1000));
        }
        // A signal interrupts the wait: that is how a stop arrives.
        if (rx_handle_timeout(lcm, wait_ms > 0 ? wait_ms : 0) < 0 && !g_stop) {
            std::fprintf(stderr, "auv-nav: LCM receive failed\n");
            return 2;
        }
        if (g_stop)
            break;
        if (node.attitude_fresh())
            node.publish_on_attitude();
        if (!o.sim_clock)
            node.set_now(system_now_us());
        // In lockstep the clock's solution waits for the step's data: the
        // clock and the simulator's sensor messages come from two senders, so
        // which is handled first varies from run to run, and a solution put
        // out between them would make the log differ (issue 14: the same
        // scenario twice gives the same messages).
        if (!node.have_time() || node.now() < next_cycle || !node.step_data_in())
            continue;
        node.publish_cycle();
        // Skip missed cycles instead of publishing a burst after a stall.
        next_cycle = tp_sat_add(next_cycle, period_us); // saturating: no stamp can overflow it
        if (next_cycle <= node.now())
            next_cycle = tp_sat_add(node.now(), period_us);
    }
    node.lockstep_leave();
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    nav::NodeOptions opt;
    bool check = false;
    if (!parse_args(argc, argv, opt, check))
        return 2;
    nav::NavConfig cfg;
    std::vector<std::string> errors;
    if (!nav::load_config(opt.config_path, cfg, errors)) {
        for (const std::string &e : errors)
            std::fprintf(stderr, "%s\n", e.c_str());
        std::fprintf(stderr, "auv-nav: %zu error(s) in %s\n", errors.size(), opt.config_path.c_str());
        return 1;
    }
    if (check) {
        std::printf("%s: ok (%d transponders)\n", opt.config_path.c_str(), cfg.n_transponders);
        return 0;
    }
    lcm_t *lcm = rx_lcm_create(opt.url.empty() ? nullptr : opt.url.c_str()); // NULL: liblcm honours LCM_DEFAULT_URL
    if (!lcm) {
        std::fprintf(stderr, "auv-nav: cannot open LCM at %s (no multicast route? see README)\n", opt.url.empty() ? "the default URL" : opt.url.c_str());
        return 2;
    }
    int rc = 2;
    {
        nav::NavNode node(opt, cfg, lcm);
        if (node.subscribe()) {
            struct sigaction sa;
            std::memset(&sa, 0, sizeof sa);
            sa.sa_handler = on_signal;
            sigaction(SIGINT, &sa, nullptr);
            sigaction(SIGTERM, &sa, nullptr);
            std::fprintf(stderr, "auv-nav: %s: %d transponders; publishing %s at %.1f Hz on the %s clock\n",
                         opt.vehicle.c_str(), cfg.n_transponders,
                         (opt.channel.empty() ? opt.vehicle + ".NAV" : opt.channel).c_str(), opt.rate_hz,
                         opt.sim_clock ? "SIM.CLOCK" : "system");
            rc = run(node, lcm, opt);
            node.print_summary();
        } else {
            std::fprintf(stderr, "auv-nav: cannot subscribe to the sensor channels\n");
        }
    }
    rx_lcm_destroy(lcm);
    return rc;
}
