// The navigation filter's configuration: sensor specifications, process
// noise, gating and trust limits, and the LBL net (transponder positions,
// turnaround times, sound speed). Read from a nav config file (see
// docs/navigation.md); python/tools/nav/navconf.py writes one from a simulator
// configuration so a simulated vehicle's filter knows what its
// instruments' datasheets would say and where the transponders were laid.
#ifndef NAV_CONFIG_HPP
#define NAV_CONFIG_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "nav/nav_meas.hpp"

namespace nav {

constexpr int kMaxTransponders = 16;

struct Transponder {
    int32_t id = 0;
    double north_m = 0, east_m = 0, depth_m = 0;
    double turnaround_s = 0;
};

struct NavConfig {
    // world origin, for latitude/longitude of the solution
    double origin_latitude_deg = 41.52;
    double origin_longitude_deg = -70.67;

    // sensor specifications (1-sigma)
    double compass_noise_rad = 0.00872665;        // 0.5 deg white
    double compass_bias_sigma_rad = 0.0174533;    // 1 deg: prior on the constant bias
    double compass_bias_walk_rad_per_sqrt_s = 1e-6;
    double gyro_noise_radps = 0.000872665;
    double attitude_noise_rad = 0.00174533;       // roll, pitch (reported, not estimated)
    double depth_noise_m = 0.02;
    double dvl_noise_mps = 0.01;                  // used when the message gives none
    // Water track also measures the water's own motion that the current
    // states do not model: shear (extra_mps) and wave orbital velocity, largest
    // at the surface and decaying with depth as exp(-depth / wave_decay_depth_m)
    // (g T^2 / 4 pi^2: 9 m for a 6 s swell).
    double dvl_water_track_extra_mps = 0.03;
    double dvl_water_track_surface_extra_mps = 0.3;
    double wave_decay_depth_m = 9.0;
    double gps_noise_m = 2.0;                     // used when the fix gives no sigma
    double lbl_range_noise_m = 1.25;

    // process model
    double accel_noise_mps2 = 0.1;                // surge/sway velocity random walk [m/s^2/sqrt(Hz)]
    double heave_accel_noise_mps2 = 0.05;
    // Near the surface waves throw the hull about: all three velocity
    // components get this random walk instead while shallower than the zone.
    double surface_zone_m = 2.0;
    double surface_accel_noise_mps2 = 0.5;
    double heading_walk_rad_per_sqrt_s = 0.002;   // gyro-driven heading model error
    double current_walk_mps_per_sqrt_s = 0.002;
    double position_walk_m_per_sqrt_s = 0.01;
    double max_predict_step_s = 0.05;             // long gaps are predicted in steps

    // initialisation
    double initial_velocity_sigma_mps = 0.5;
    double initial_current_sigma_mps = 0.3;
    bool have_initial_position = false;           // else the first GPS fix aligns
    double initial_north_m = 0, initial_east_m = 0, initial_position_sigma_m = 5.0;

    // innovation gating and recovery
    double gate_probability = 0.999;              // chi-square quantile of the NIS gate; 1: no gate
    int reset_after[5] = {40, 20, 25, 5, 6};      // consecutive rejections before a reset, per sensor

    // trust
    double degraded_sigma_m = 10.0;               // horizontal 1-sigma above this: DEGRADED
    double invalid_sigma_m = 50.0;                // ... above this: INVALID
    double degraded_heading_sigma_rad = 0.0872665;  // 5 deg
    double dvl_timeout_s = 10.0;                  // no velocity aiding this long: DEGRADED
    double input_timeout_s = 2.0;                 // no measurement at all this long: INVALID
    double heading_timeout_s = 5.0;               // no compass this long: INVALID
    double aid_window_s[5] = {1.0, 1.0, 2.0, 5.0, 30.0};  // status bits: accepted this recently

    // LBL
    double sound_speed_mps = 0;                   // 0: the sound speed in each LBL message
    double sound_speed_gradient_per_m = 0;
    Transponder transponders[kMaxTransponders];
    int n_transponders = 0;

    // altitude above the seabed: passed through from the altimeter or the DVL
    double altitude_timeout_s = 2.0;              // older than this: unknown (-1)

    // time ordering
    double history_s = 10.0;                      // how late a measurement may arrive

    // derived: chi-square gates for 1..3 degrees of freedom
    double gate_chi2[4] = {0, 10.828, 13.816, 16.266};

    const Transponder *transponder(int32_t id) const;
    void derive();                                // recompute gate_chi2 from gate_probability
};

// Read a nav config file over the defaults. Every error is appended as
// "file:line:col: message"; returns false if there was any.
bool load_config(const std::string &path, NavConfig &cfg, std::vector<std::string> &errors);
bool parse_config(const std::string &name, const std::string &text, NavConfig &cfg,
                  std::vector<std::string> &errors);

}  // namespace nav

#endif
