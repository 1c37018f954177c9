// Where the filter meets LCM: the sensor channels it reads, message ->
// Measurement conversion (with the checks a driver's output deserves), and
// the filter's estimate -> nav_solution_t / nav_filter_status_t. Shared by
// the live process (auv-nav) and the log replay (auv-nav-replay), so both
// run exactly the same code on the same messages.
#ifndef NAV_LCM_HPP
#define NAV_LCM_HPP

#include <string>

extern "C" {
#include "auv/auv_nav_filter_status_t.h"
#include "auv/auv_nav_solution_t.h"
#include "common/auv_types.h"
#include "common/time_policy.h"
}

#include "nav/nav_filter.hpp"
#include "nav/nav_status.hpp"

namespace nav {

struct SensorChannel {
    Sensor sensor;
    const char *topic;          // channel suffix: <VEHICLE>.<topic>
    const char *type;           // LCM type name
};
extern const SensorChannel kSensorChannels[kSensors];

// What became of one decoded message.
// IMPLAUSIBLE: a non-finite number, or one outside what the instrument can
// report (a depth of 1e300 m, a heading of 40 rad): a broken driver, never data.
enum class Convert { OK, NOT_VALID, WRONG_VEHICLE, IMPLAUSIBLE };

// msg is the decoded struct of kSensorChannels[sensor].type.
Convert to_measurement(Sensor sensor, const void *msg, const char *vehicle, Measurement &out);

// An altimeter_t's altitude, or a negative value if it has none to give.
double altimeter_reading(const void *msg, const char *vehicle, int64_t *utime);

// The estimate s (already at utime) as a nav_solution_t, with altitude_m
// (-1: unknown). Strings point into vehicle, which must outlive out.
void fill_solution(const FilterState &s, const NavStatus &st, const NavConfig &c, double altitude_m, char *vehicle,
                   int64_t utime, auv_nav_solution_t &out);
// time_drops / clock_drops: the time rule's counters per tp_reason (NULL: none).
void fill_filter_status(const NavFilter &f, const NavStatus &st, char *vehicle, int64_t utime,
                        auv_nav_filter_status_t &out, const tp_counts *time_drops = nullptr,
                        const tp_counts *clock_drops = nullptr);

// latitude/longitude of a local north/east on the world origin's tangent plane
void local_to_latlon(const NavConfig &c, double north_m, double east_m, double &lat_deg, double &lon_deg);

}  // namespace nav

#endif
