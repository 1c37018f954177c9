// Message -> measurement: what a broken driver sends never reaches the filter.
#include <cmath>
#include <cstring>

#include "../../harness/unit.h"
#include "nav/nav_lcm.hpp"

extern "C" {
#include "auv/auv_ahrs_t.h"
#include "auv/auv_depth_t.h"
#include "auv/auv_dvl_t.h"
#include "auv/auv_gps_fix_t.h"
#include "auv/auv_lbl_ranges_t.h"
}

using nav::Convert;

TEST(conversion_drops_invalid_foreign_and_implausible_messages)
{
    char v1[] = "AUV1", v2[] = "AUV2";
    nav::Measurement m;
    auv_ahrs_t a = {};
    a.utime = 5;
    a.vehicle = v1;
    a.valid = 1;
    a.heading_rad = 1.0;
    CHECK(nav::to_measurement(nav::SENSOR_AHRS, &a, "AUV1", m) == Convert::OK);
    CHECK(m.utime == 5 && m.sensor == nav::SENSOR_AHRS && m.ahrs.heading_rad == 1.0);
    a.vehicle = v2;
    CHECK(nav::to_measurement(nav::SENSOR_AHRS, &a, "AUV1", m) == Convert::WRONG_VEHICLE);
    a.vehicle = v1;
    a.heading_rad = NAN;
    CHECK(nav::to_measurement(nav::SENSOR_AHRS, &a, "AUV1", m) == Convert::IMPLAUSIBLE);
    a.heading_rad = 40.0;
    CHECK(nav::to_measurement(nav::SENSOR_AHRS, &a, "AUV1", m) == Convert::IMPLAUSIBLE);
    a.heading_rad = 1.0;
    a.valid = 0;
    CHECK(nav::to_measurement(nav::SENSOR_AHRS, &a, "AUV1", m) == Convert::NOT_VALID);

    auv_depth_t d = {};
    d.vehicle = v1;
    d.valid = 1;
    d.depth_m = 1e300;
    CHECK(nav::to_measurement(nav::SENSOR_DEPTH, &d, "AUV1", m) == Convert::IMPLAUSIBLE);

    auv_dvl_t dv = {};
    dv.vehicle = v1;
    dv.mode = AUV_DVL_T_MODE_NONE;
    CHECK(nav::to_measurement(nav::SENSOR_DVL, &dv, "AUV1", m) == Convert::NOT_VALID);
    dv.mode = AUV_DVL_T_MODE_WATER_TRACK;
    dv.velocity_mps[0] = 1.5;
    dv.velocity_sigma_mps = 0.01;
    CHECK(nav::to_measurement(nav::SENSOR_DVL, &dv, "AUV1", m) == Convert::OK && !m.dvl.bottom_lock);
    dv.velocity_mps[2] = -INFINITY;
    CHECK(nav::to_measurement(nav::SENSOR_DVL, &dv, "AUV1", m) == Convert::IMPLAUSIBLE);

    auv_gps_fix_t g = {};
    g.vehicle = v1;
    g.fix_type = AUV_GPS_FIX_T_FIX_NONE;
    CHECK(nav::to_measurement(nav::SENSOR_GPS, &g, "AUV1", m) == Convert::NOT_VALID);

    // LBL: implausible replies are dropped one by one, the rest kept
    int32_t ids[3] = {1, 2, 3};
    double tw[3] = {0.5, NAN, -1.0}, ta[3] = {0.05, 0.05, 0.05};
    auv_lbl_ranges_t l = {};
    l.vehicle = v1;
    l.sound_speed_mps = 1500;
    l.n_replies = 3;
    l.transponder_id = ids;
    l.two_way_travel_s = tw;
    l.turnaround_s = ta;
    CHECK(nav::to_measurement(nav::SENSOR_LBL, &l, "AUV1", m) == Convert::OK);
    CHECK(m.lbl.n == 1 && m.lbl.id[0] == 1 && m.lbl.two_way_travel_s[0] == 0.5);
    tw[0] = 100.0;
    CHECK(nav::to_measurement(nav::SENSOR_LBL, &l, "AUV1", m) == Convert::IMPLAUSIBLE);
}
