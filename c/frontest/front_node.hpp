// auv-front-estimate's process around the fit: <VEHICLE>.CTD and
// <VEHICLE>.NAV in (count-and-drop through c/common/lcm_rx, the time rule of
// c/common/time_policy), front_estimate_t out on <VEHICLE>.FRONT_ESTIMATE at
// the stated rate of mission time (SIM.CLOCK, or the host's clock).
#ifndef FRONTEST_FRONT_NODE_HPP
#define FRONTEST_FRONT_NODE_HPP

#include <cstdint>
#include <string>

#include <lcm/lcm.h>

extern "C" {
#include "common/lcm_rx.h"
#include "common/time_policy.h"
}

#include "frontest/front_fit.hpp"
#include "frontest/front_intake.hpp"

namespace frontest {

struct NodeOptions {
    std::string vehicle, url, channel;  // channel "": <VEHICLE>.FRONT_ESTIMATE
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
    bool time_ok(tp_input &in, int64_t stamp, const char *channel);
    void publish(const FitResult &r, const std::vector<Sample> &xs);

    NodeOptions opt_;
    lcm_t *lcm_;
    std::string vehicle_;
    Intake intake_;
    rx_sub_t *ctd_sub_ = nullptr, *nav_sub_ = nullptr, *clock_sub_ = nullptr;
    tp_clock clock_;
    tp_term term_ = {};
    tp_input ctd_order_ = {}, nav_order_ = {};
    tp_counts time_drops_ = {}, clock_drops_ = {};
    bool have_time_ = false;
    int64_t now_ = 0, next_fit_ = 0;
    Front last_ok_;
    bool have_ok_ = false;
    Status last_status_ = Status::TOO_FEW;
    bool logged_status_ = false;
    uint64_t published_ = 0;
};

}  // namespace frontest

#endif
