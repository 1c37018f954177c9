// auv-front-estimate's process around the fit: <VEHICLE>.CTD and
// <VEHICLE>.NAV in (count-and-drop through c/common/lcm_rx, the time rule of
// c/common/time_policy), the teammates' front summaries from the team-link
// frames of <VEHICLE>.MODEM_RX; front_estimate_t out at the stated rate of
// mission time (SIM.CLOCK, or the host's clock): its own samples' fit on
// <VEHICLE>.FRONT_ESTIMATE, with the teammates' summaries on <VEHICLE>.FRONT_TEAM.
#ifndef FRONTEST_FRONT_NODE_HPP
#define FRONTEST_FRONT_NODE_HPP

#include <cstdint>
#include <map>
#include <string>

#include <lcm/lcm.h>

extern "C" {
#include "common/lcm_rx.h"
#include "common/time_policy.h"
}

#include "frontest/front_fit.hpp"
#include "frontest/front_intake.hpp"
#include "frontest/front_summary.hpp"

namespace frontest {

struct NodeOptions {
    std::string vehicle, url, channel;  // channel "": <VEHICLE>.FRONT_ESTIMATE
    std::string team_channel;           // "": <VEHICLE>.FRONT_TEAM
    double rate_hz = 0.2;
    bool sim_clock = true;
    IntakeOptions intake;
    FitOptions fit;
};

class FrontNode {
public:
    FrontNode(const NodeOptions &opt, lcm_t *lcm);
    ~FrontNode();
    bool subscribe();
    bool have_time() const { return have_time_; }
    int64_t now() const { return now_; }
    // A clock reading under the time rule; false when refused.
    bool set_now(int64_t t);
    // Places waiting readings; fits and publishes when one is due.
    void cycle();
    void print_summary() const;

private:
    static void on_ctd(const char *channel, const void *msg, int64_t recv_utime, void *user);
    static void on_nav(const char *channel, const void *msg, int64_t recv_utime, void *user);
    static void on_clock(const char *channel, const void *msg, int64_t recv_utime, void *user);
    static void on_modem(const char *channel, const void *msg, int64_t recv_utime, void *user);
    bool time_ok(tp_input &in, int64_t stamp, const char *channel);
    void publish(const std::string &channel, const FitResult &r, const std::vector<Sample> &xs, int peers);
    FitResult team_fit(const FitResult &own, const std::vector<Sample> &xs);

    struct Peer {
        int64_t heard;      // arrival of its newest summary [us]
        Prior prior;
    };

    NodeOptions opt_;
    lcm_t *lcm_;
    std::string vehicle_;
    Intake intake_;
    rx_sub_t *ctd_sub_ = nullptr, *nav_sub_ = nullptr, *clock_sub_ = nullptr, *modem_sub_ = nullptr;
    std::map<std::string, Peer> peers_;  // by the sending vehicle
    uint64_t summaries_heard_ = 0, frames_bad_ = 0;
    tp_clock clock_;
    tp_term term_ = {};
    tp_input ctd_order_ = {}, nav_order_ = {};
    tp_counts time_drops_ = {}, clock_drops_ = {};
    bool have_time_ = false;
    int64_t now_ = 0, next_fit_ = 0;
    Front last_ok_, last_team_ok_;
    bool have_ok_ = false, have_team_ok_ = false;
    Status last_status_ = Status::TOO_FEW;
    bool logged_status_ = false;
    uint64_t published_ = 0;
};

}  // namespace frontest

#endif
