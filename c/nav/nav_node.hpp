// The live navigation process around the filter: the vehicle's sensor
// channels in (count-and-drop through c/common/lcm_rx), the solution, the
// filter status and the process health out.
#ifndef NAV_NODE_HPP
#define NAV_NODE_HPP

#include <cstdint>
#include <string>

#include <lcm/lcm.h>

extern "C" {
#include "common/lcm_rx.h"
#include "common/time_policy.h"
#include "managers/mgr_lockstep.h"
}

#include "nav/nav_filter.hpp"
#include "nav/nav_lcm.hpp"

namespace nav {

struct NodeOptions {
    std::string config_path, vehicle = "AUV1", url;  // url "": liblcm's default ($LCM_DEFAULT_URL)
    std::string channel;        // solution channel; default <VEHICLE>.NAV
    std::string status_channel; // default <VEHICLE>.NAV_STATUS
    double rate_hz = 20.0;
    bool sim_clock = true;
    int64_t future_tol_us = TP_FUTURE_TOLERANCE_US;
    int64_t max_clock_jump_us = TP_MAX_CLOCK_JUMP_US;
};

struct ConvertCounts {
    uint64_t not_valid = 0, wrong_vehicle = 0, implausible = 0;
};

class NavNode {
public:
    NavNode(const NodeOptions &opt, const NavConfig &cfg, lcm_t *lcm);
    ~NavNode();
    bool subscribe();           // false if any subscription failed

    // The mission clock: SIM.CLOCK's time (sim) or the host's (system).
    bool have_time() const { return have_time_; }
    int64_t now() const { return now_us_; }
    // A system clock reading, under the same time rule as SIM.CLOCK.
    void set_now(int64_t t) { clock_reading(t, "system clock"); }

    // One output cycle at the mission time now(): the solution (once aligned)
    // if the compass has been silent for two of its intervals (and 1/rate), and,
    // once a second, filter status and health.
    void publish_cycle();
    // The solution at the newest compass message's time, as soon as it is in:
    // the pilot's attitude and rate loops cannot wait for the next cycle (a
    // cycle's hold added 50-100 ms, which made the pitch loop oscillate).
    bool attitude_fresh() const { return attitude_fresh_; }
    void publish_on_attitude();
    void print_summary() const;
    // Lockstep (docs/multihil.md): each turn of the loop. The filter reports
    // step n once it has handled the clock of step n and its simulator's
    // report of step n: every sensor message of the step is in and every
    // solution it brought is out before the world's next step.
    void lockstep_poll();
    // Lockstep: has this vehicle's simulator sent all its data of the step
    // under way (its report of the step is in)? True without a simulator in
    // the lockstep.
    bool step_data_in() const;
    // The manager-style participant that sends this filter's reports
    // ("<VEHICLE>.NAV"); one stopping sends LEAVE.
    void lockstep_leave();

    const NavFilter &filter() const { return filter_; }
    uint64_t decode_errors() const;

private:
    static void on_sensor(const char *channel, const void *msg, int64_t recv_utime, void *user);
    static void on_clock(const char *channel, const void *msg, int64_t recv_utime, void *user);
    static void on_altimeter(const char *channel, const void *msg, int64_t recv_utime, void *user);
    static void on_lockstep(const lcm_recv_buf_t *rbuf, const char *channel, void *user);
    void publish_health();
    bool clock_reading(int64_t t, const char *source);
    void publish_solution(int64_t t, const NavStatus &st);

    NodeOptions opt_;
    lcm_t *lcm_;
    NavFilter filter_;
    FilterState scratch_;       // the estimate at the cycle time
    std::string vehicle_;       // mutable copy: LCM messages take char *
    rx_sub_t *subs_[kSensors] = {};
    rx_sub_t *clock_sub_ = nullptr;
    rx_sub_t *altimeter_sub_ = nullptr;
    rx_raw_t *lockstep_sub_ = nullptr;              // raw: only its simulator's reports are decoded
    uint64_t lockstep_decode_errors_ = 0;
    mgr_lockstep lockstep_;
    std::string sim_participant_;       // "<VEHICLE>.sim"
    int64_t sim_done_ = -1;             // the newest step its simulator reported done
    bool sim_seen_ = false;             // its simulator takes part in the lockstep
    struct SubCtx {
        NavNode *node;
        Sensor sensor;
    } ctx_[kSensors];
    ConvertCounts convert_;
    int64_t now_us_ = 0;
    bool have_time_ = false;
    // The time rule (docs/channels.md, "Time and timestamps").
    tp_clock clock_;
    tp_term clock_term_ = {};
    tp_input order_[kSensors] = {};
    tp_input alt_order_ = {};
    tp_counts time_drops_ = {};
    tp_counts clock_drops_ = {};
    int64_t next_status_us_ = 0;
    double cpu_s_at_health_ = 0, wall_s_at_health_ = 0;
    uint64_t published_ = 0;
    bool attitude_fresh_ = false;
    int64_t last_out_us_ = 0;           // time of the newest solution out
    int64_t attitude_out_us_ = 0;       // time of the last compass-driven solution
    int64_t attitude_interval_us_ = 0;  // between the last two of them
};

}  // namespace nav

#endif
