// Measurements as the filter sees them: plain values with their time of
// validity, independent of LCM (nav_lcm.cpp converts the messages). Fixed
// size, so the time-ordering history stores them by value.
#ifndef NAV_MEAS_HPP
#define NAV_MEAS_HPP

#include <cstdint>

namespace nav {

// Same order as auv.nav_filter_status_t's SENSOR_* constants.
enum Sensor { SENSOR_AHRS = 0, SENSOR_DEPTH = 1, SENSOR_DVL = 2, SENSOR_GPS = 3, SENSOR_LBL = 4 };
constexpr int kSensors = 5;
const char *sensor_name(int sensor);

struct AhrsMeas {
    double roll_rad, pitch_rad, heading_rad;
    double p_radps, q_radps, r_radps;
};

struct DepthMeas {
    double depth_m;
};

struct DvlMeas {
    bool bottom_lock;           // false: water track (velocity through the water)
    double velocity_mps[3];     // body x, y, z
    double sigma_mps;           // <= 0: the configured figure
    double altitude_m;          // its range to the bottom; < 0 none
};

struct GpsMeas {
    double north_m, east_m;
    double sigma_m;             // <= 0: the configured figure
};

constexpr int kMaxReplies = 16;
struct LblMeas {
    double sound_speed_mps;     // what the receiver assumes (used unless configured)
    int n;
    int32_t id[kMaxReplies];
    double two_way_travel_s[kMaxReplies];
};

struct Measurement {
    int64_t utime;              // time of validity [us]
    Sensor sensor;
    union {
        AhrsMeas ahrs;
        DepthMeas depth;
        DvlMeas dvl;
        GpsMeas gps;
        LblMeas lbl;
    };
};

}  // namespace nav

#endif
