// auv-front-estimate: a vehicle's on-board estimate of an ocean front
// (docs/sampling.md, "The on-board front estimator").
//
//   auv-front-estimate --vehicle AUV1 [--lcm-url URL] [--clock sim|system] [--rate HZ]
//                      [--channel CH] [--team-channel CH] [--max-age S] [--max-depth M] [--bin M]
//                      [--min-samples N] [--min-contrast C] [--meander-span M]
//
// Reads <VEHICLE>.CTD (ctd_t) and <VEHICLE>.NAV (nav_solution_t), and the
// teammates' front summaries in the team-link frames of <VEHICLE>.MODEM_RX;
// fits the front model of docs/sampling.md to the temperatures at their
// positions by Levenberg-Marquardt and publishes front_estimate_t at --rate
// Hz of mission time, from its own samples on <VEHICLE>.FRONT_ESTIMATE and
// with the teammates' summaries as priors on <VEHICLE>.FRONT_TEAM: the
// parameters, their sigmas from (J^T J)^-1 sigma^2, the samples used and
// dropped by reason, OK / TOO_FEW / DIVERGED with a text. --clock sim follows SIM.CLOCK
// (nothing is published before it ticks), system the host's. SIGINT/SIGTERM
// end it cleanly (exit 0); 2: usage or LCM failure.
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>

#include "frontest/front_node.hpp"

namespace {

volatile sig_atomic_t g_stop = 0;

void on_signal(int) { g_stop = 1; }

void usage(FILE *out)
{
    std::fprintf(out,
                 "usage: auv-front-estimate --vehicle ID [--lcm-url URL] [--clock sim|system] [--rate HZ]\n"
                 "                          [--channel CH] [--team-channel CH] [--max-age S] [--max-depth M] [--bin M]\n"
                 "                          [--min-samples N] [--min-contrast C] [--meander-span M]\n"
                 "  --lcm-url URL       LCM URL (default: $LCM_DEFAULT_URL, else liblcm's default);\n"
                 "                      --url is the old spelling of it\n"
                 "  --clock sim|system  SIM.CLOCK's time (default) or the host's\n"
                 "  --rate HZ           estimates a second of mission time (default 0.2)\n"
                 "  --channel CH        its own samples' estimate (default <VEHICLE>.FRONT_ESTIMATE)\n"
                 "  --team-channel CH   with the teammates' summaries (default <VEHICLE>.FRONT_TEAM)\n"
                 "  --max-age S         readings and teammates' summaries older than this are dropped (default 1800)\n"
                 "  --max-depth M       readings deeper than this are not of the upper water (default 15)\n"
                 "  --bin M             readings averaged over this much of the path (default 1)\n"
                 "  --min-samples N     bins a fit needs (default 30)\n"
                 "  --min-contrast C    degC between the waters a fit needs (default 0.5)\n"
                 "  --meander-span M    metres along the front before the meander is fitted (default 400)\n");
}

bool number(const char *opt, const char *v, double lo, double hi, double &out)
{
    char *end = nullptr;
    const double x = std::strtod(v, &end);
    if (!end || end == v || *end || !(x >= lo && x <= hi)) {
        std::fprintf(stderr, "auv-front-estimate: %s wants a number from %g to %g, not '%s'\n", opt, lo, hi, v);
        return false;
    }
    out = x;
    return true;
}

bool parse_args(int argc, char **argv, frontest::NodeOptions &o)
{
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            usage(stdout);
            std::exit(0);
        }
        const char *v = i + 1 < argc ? argv[i + 1] : nullptr;
        if (!v) {
            std::fprintf(stderr, "auv-front-estimate: bad or incomplete option '%s'\n", a.c_str());
            return false;
        }
        double x = 0;
        bool ok = true;
        if (a == "--vehicle") o.vehicle = v;
        else if (a == "--lcm-url" || a == "--url") o.url = v;
        else if (a == "--channel") o.channel = v;
        else if (a == "--team-channel") o.team_channel = v;
        else if (a == "--clock" && (!std::strcmp(v, "sim") || !std::strcmp(v, "system"))) o.sim_clock = !std::strcmp(v, "sim");
        else if (a == "--rate") ok = number("--rate", v, 1e-3, 100, o.rate_hz);
        else if (a == "--max-age") ok = number("--max-age", v, 1, 1e6, o.intake.max_age_s);
        else if (a == "--max-depth") ok = number("--max-depth", v, 0, 11000, o.intake.max_depth_m);
        else if (a == "--bin") ok = number("--bin", v, 0.01, 1000, o.intake.bin_m);
        else if (a == "--min-samples") {
            ok = number("--min-samples", v, 10, 1e6, x);
            o.fit.min_samples = static_cast<int>(x);
        } else if (a == "--min-contrast") ok = number("--min-contrast", v, 0, 50, o.fit.min_contrast_c);
        else if (a == "--meander-span") ok = number("--meander-span", v, 0, 1e7, o.fit.meander_span_m);
        else {
            std::fprintf(stderr, "auv-front-estimate: bad or incomplete option '%s'\n", a.c_str());
            return false;
        }
        if (!ok)
            return false;
        i++;
    }
    if (o.vehicle.empty()) {
        usage(stderr);
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

}  // namespace

int main(int argc, char **argv)
{
    frontest::NodeOptions opt;
    if (!parse_args(argc, argv, opt))
        return 2;
    lcm_t *lcm = rx_lcm_create(opt.url.empty() ? nullptr : opt.url.c_str());
    if (!lcm) {
        std::fprintf(stderr, "auv-front-estimate: cannot open LCM at %s\n", opt.url.empty() ? "the default URL" : opt.url.c_str());
        return 2;
    }
    int rc = 2;
    {
        frontest::FrontNode node(opt, lcm);
        if (node.subscribe()) {
            struct sigaction sa;
            std::memset(&sa, 0, sizeof sa);
            sa.sa_handler = on_signal;
            sigaction(SIGINT, &sa, nullptr);
            sigaction(SIGTERM, &sa, nullptr);
            std::fprintf(stderr, "auv-front-estimate: %s: fitting %s.CTD at %s.NAV; publishing every %g s on the %s clock\n",
                         opt.vehicle.c_str(), opt.vehicle.c_str(), opt.vehicle.c_str(), 1 / opt.rate_hz,
                         opt.sim_clock ? "SIM.CLOCK" : "system");
            rc = 0;
            while (!g_stop) {
                if (rx_handle_timeout(lcm, 50) < 0 && !g_stop) {
                    std::fprintf(stderr, "auv-front-estimate: LCM receive failed\n");
                    rc = 2;
                    break;
                }
                if (!opt.sim_clock)
                    node.set_now(system_now_us());
                node.cycle();
            }
            node.print_summary();
        } else {
            std::fprintf(stderr, "auv-front-estimate: cannot subscribe\n");
        }
    }
    rx_lcm_destroy(lcm);
    return rc;
}
