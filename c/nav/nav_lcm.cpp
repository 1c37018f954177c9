#include "nav/nav_lcm.hpp"

#include <cmath>
#include <cstring>

extern "C" {
#include "auv/auv_ahrs_t.h"
#include "auv/auv_altimeter_t.h"
#include "auv/auv_depth_t.h"
#include "auv/auv_dvl_t.h"
#include "auv/auv_gps_fix_t.h"
#include "auv/auv_lbl_ranges_t.h"
}

namespace nav {

static_assert(STATUS_ALIGNED == AUV_NAV_SOLUTION_T_STATUS_ALIGNED && STATUS_DVL_BOTTOM == AUV_NAV_SOLUTION_T_STATUS_DVL_BOTTOM &&
                  STATUS_DVL_WATER == AUV_NAV_SOLUTION_T_STATUS_DVL_WATER && STATUS_GPS == AUV_NAV_SOLUTION_T_STATUS_GPS &&
                  STATUS_LBL == AUV_NAV_SOLUTION_T_STATUS_LBL && STATUS_DEGRADED == AUV_NAV_SOLUTION_T_STATUS_DEGRADED &&
                  STATUS_INVALID == AUV_NAV_SOLUTION_T_STATUS_INVALID,
              "status bits differ from lcmtypes/nav_solution_t.lcm");
static_assert(SENSOR_AHRS == AUV_NAV_FILTER_STATUS_T_SENSOR_AHRS && SENSOR_DEPTH == AUV_NAV_FILTER_STATUS_T_SENSOR_DEPTH &&
                  SENSOR_DVL == AUV_NAV_FILTER_STATUS_T_SENSOR_DVL && SENSOR_GPS == AUV_NAV_FILTER_STATUS_T_SENSOR_GPS &&
                  SENSOR_LBL == AUV_NAV_FILTER_STATUS_T_SENSOR_LBL,
              "sensor indices differ from lcmtypes/nav_filter_status_t.lcm");

const SensorChannel kSensorChannels[kSensors] = {
    {SENSOR_AHRS, "AHRS", "ahrs_t"},
    {SENSOR_DEPTH, "DEPTH", "depth_t"},
    {SENSOR_DVL, "DVL", "dvl_t"},
    {SENSOR_GPS, "GPS", "gps_fix_t"},
    {SENSOR_LBL, "LBL", "lbl_ranges_t"},
};

namespace {

// Every value finite and within +-limit.
bool plausible(std::initializer_list<double> v, double limit)
{
    for (double x : v)
        if (!std::isfinite(x) || std::fabs(x) > limit)
            return false;
    return true;
}

}  // namespace

Convert to_measurement(Sensor sensor, const void *msg, const char *vehicle, Measurement &out)
{
    std::memset(&out, 0, sizeof out);
    out.sensor = sensor;
    // Every sensor message starts with int64_t utime (lcm-gen's structs follow
    // the .lcm field order); a negative time is no time.
    const int64_t utime = *static_cast<const int64_t *>(msg);
    if (utime < 0)
        return Convert::IMPLAUSIBLE;
    switch (sensor) {
    case SENSOR_AHRS: {
        const auto *m = static_cast<const auv_ahrs_t *>(msg);
        out.utime = m->utime;
        if (vehicle && std::strcmp(m->vehicle, vehicle) != 0) return Convert::WRONG_VEHICLE;
        if (!m->valid) return Convert::NOT_VALID;
        if (!plausible({m->roll_rad, m->pitch_rad, m->heading_rad}, 4 * M_PI) ||
            !plausible({m->p_radps, m->q_radps, m->r_radps}, 20.0))
            return Convert::IMPLAUSIBLE;
        out.ahrs = {m->roll_rad, m->pitch_rad, m->heading_rad, m->p_radps, m->q_radps, m->r_radps};
        return Convert::OK;
    }
    case SENSOR_DEPTH: {
        const auto *m = static_cast<const auv_depth_t *>(msg);
        out.utime = m->utime;
        if (vehicle && std::strcmp(m->vehicle, vehicle) != 0) return Convert::WRONG_VEHICLE;
        if (!m->valid) return Convert::NOT_VALID;
        if (!plausible({m->depth_m}, 12000.0)) return Convert::IMPLAUSIBLE;
        out.depth.depth_m = m->depth_m;
        return Convert::OK;
    }
    case SENSOR_DVL: {
        const auto *m = static_cast<const auv_dvl_t *>(msg);
        out.utime = m->utime;
        if (vehicle && std::strcmp(m->vehicle, vehicle) != 0) return Convert::WRONG_VEHICLE;
        if (m->mode != AUV_DVL_T_MODE_BOTTOM_LOCK && m->mode != AUV_DVL_T_MODE_WATER_TRACK) return Convert::NOT_VALID;
        if (!plausible({m->velocity_mps[0], m->velocity_mps[1], m->velocity_mps[2]}, 20.0) ||
            !plausible({m->velocity_sigma_mps}, 10.0))
            return Convert::IMPLAUSIBLE;
        out.dvl.bottom_lock = m->mode == AUV_DVL_T_MODE_BOTTOM_LOCK;
        for (int i = 0; i < 3; i++)
            out.dvl.velocity_mps[i] = m->velocity_mps[i];
        out.dvl.sigma_mps = m->velocity_sigma_mps;
        out.dvl.altitude_m = std::isfinite(m->altitude_m) && m->altitude_m < 12000 ? m->altitude_m : -1.0;
        return Convert::OK;
    }
    case SENSOR_GPS: {
        const auto *m = static_cast<const auv_gps_fix_t *>(msg);
        out.utime = m->utime;
        if (vehicle && std::strcmp(m->vehicle, vehicle) != 0) return Convert::WRONG_VEHICLE;
        if (m->fix_type == AUV_GPS_FIX_T_FIX_NONE) return Convert::NOT_VALID;
        if (!plausible({m->north_m, m->east_m}, 1e7) || !plausible({m->horizontal_sigma_m}, 1e4))
            return Convert::IMPLAUSIBLE;
        out.gps = {m->north_m, m->east_m, m->horizontal_sigma_m};
        return Convert::OK;
    }
    case SENSOR_LBL: {
        const auto *m = static_cast<const auv_lbl_ranges_t *>(msg);
        out.utime = m->utime;
        if (vehicle && std::strcmp(m->vehicle, vehicle) != 0) return Convert::WRONG_VEHICLE;
        if (m->n_replies <= 0) return Convert::NOT_VALID;
        if (!plausible({m->sound_speed_mps}, 2000.0)) return Convert::IMPLAUSIBLE;
        out.lbl.sound_speed_mps = m->sound_speed_mps;
        int n = 0;
        for (int i = 0; i < m->n_replies && n < kMaxReplies; i++) {
            if (!plausible({m->two_way_travel_s[i]}, 60.0) || m->two_way_travel_s[i] <= 0)
                continue;           // no transponder is 45 km away
            out.lbl.id[n] = m->transponder_id[i];
            out.lbl.two_way_travel_s[n++] = m->two_way_travel_s[i];
        }
        out.lbl.n = n;
        return n > 0 ? Convert::OK : Convert::IMPLAUSIBLE;
    }
    }
    return Convert::NOT_VALID;
}

double altimeter_reading(const void *msg, const char *vehicle, int64_t *utime)
{
    const auto *m = static_cast<const auv_altimeter_t *>(msg);
    *utime = m->utime;
    if ((vehicle && std::strcmp(m->vehicle, vehicle) != 0) || !m->valid || m->utime < 0 ||
        !plausible({m->altitude_m}, 12000.0) || !(m->altitude_m > 0))
        return -1.0;
    return m->altitude_m;
}

void local_to_latlon(const NavConfig &c, double north_m, double east_m, double &lat_deg, double &lon_deg)
{
    // WGS-84 radii of curvature at the origin (as python/sim/geo.py)
    const double a = 6378137.0, e2 = 6.69437999014e-3;
    const double s = std::sin(c.origin_latitude_deg * M_PI / 180.0);
    const double d = 1.0 - e2 * s * s;
    const double rm = a * (1.0 - e2) / std::pow(d, 1.5), rn = a / std::sqrt(d);
    lat_deg = c.origin_latitude_deg + north_m / rm * 180.0 / M_PI;
    lon_deg = c.origin_longitude_deg + east_m / (rn * std::cos(c.origin_latitude_deg * M_PI / 180.0)) * 180.0 / M_PI;
}

void fill_solution(const FilterState &s, const NavStatus &st, const NavConfig &c, double altitude_m, char *vehicle,
                   int64_t utime, auv_nav_solution_t &out)
{
    std::memset(&out, 0, sizeof out);
    out.utime = utime;
    out.vehicle = vehicle;
    out.source = AUV_NAV_SOLUTION_T_SOURCE_EKF;
    out.status = st.bits;
    out.north_m = s.x(PN);
    out.east_m = s.x(PE);
    out.depth_m = s.x(PD);
    local_to_latlon(c, out.north_m, out.east_m, out.latitude_deg, out.longitude_deg);
    out.altitude_m = altitude_m;
    out.roll_rad = s.in.roll_rad;
    out.pitch_rad = s.in.pitch_rad;
    out.heading_rad = wrap_2pi(s.x(PSI));
    out.u_mps = s.x(VU);
    out.v_mps = s.x(VV);
    out.w_mps = s.x(VW);
    out.p_radps = s.in.p_radps;
    out.q_radps = s.in.q_radps;
    out.r_radps = s.in.r_radps;
    const Vec3 vn = body_to_ned(s.in.roll_rad, s.in.pitch_rad, s.x(PSI)) * s.x.segment<3>(VU);
    out.speed_over_ground_mps = std::hypot(vn(0), vn(1));
    out.course_over_ground_rad = wrap_2pi(std::atan2(vn(1), vn(0)));
    const double att = c.attitude_noise_rad * c.attitude_noise_rad;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            out.position_cov_m2[i][j] = s.P(PN + i, PN + j);
            out.velocity_cov_m2ps2[i][j] = s.P(VU + i, VU + j);
            out.attitude_cov_rad2[i][j] = 0;
        }
    out.attitude_cov_rad2[0][0] = att;
    out.attitude_cov_rad2[1][1] = att;
    out.attitude_cov_rad2[2][2] = s.P(PSI, PSI);
}

static int32_t clamp32(uint64_t v) { return static_cast<int32_t>(v > INT32_MAX ? INT32_MAX : v); }

void fill_filter_status(const NavFilter &f, const NavStatus &st, char *vehicle, int64_t utime,
                        auv_nav_filter_status_t &out, const tp_counts *time_drops, const tp_counts *clock_drops)
{
    std::memset(&out, 0, sizeof out);
    out.utime = utime;
    out.vehicle = vehicle;
    out.trusted = st.trusted;
    out.position_sigma_m = st.position_sigma_m;
    out.heading_sigma_rad = st.heading_sigma_rad;
    const FilterState &s = f.state();
    for (int k = 0; k < kSensors; k++) {
        const SensorStats &ss = f.stats().sensor[k];
        out.accepted[k] = static_cast<int32_t>(ss.accepted > INT32_MAX ? INT32_MAX : ss.accepted);
        out.rejected[k] = static_cast<int32_t>(ss.rejected > INT32_MAX ? INT32_MAX : ss.rejected);
        out.last_nis[k] = s.last_nis[k];
        out.last_update_utime[k] = s.last_accept_utime[k];
    }
    if (time_drops) {
        out.dropped_invalid_time = clamp32(time_drops->n[TP_INVALID]);
        out.dropped_future = clamp32(time_drops->n[TP_FUTURE]);
        out.dropped_out_of_order = clamp32(time_drops->n[TP_OUT_OF_ORDER]);
    }
    if (clock_drops) {
        out.clock_invalid = clamp32(clock_drops->n[TP_INVALID]);
        out.clock_backwards = clamp32(clock_drops->n[TP_BACKWARDS]);
        out.clock_jumps = clamp32(clock_drops->n[TP_JUMP]);
        out.clock_old_term = clamp32(clock_drops->n[TP_OLD_TERM]);
    }
}

}  // namespace nav
