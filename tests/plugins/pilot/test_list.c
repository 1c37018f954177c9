/* The list the harness runs (tests/plugins/common/plugin_test.h). */
#include "../common/plugin_test.h"
#include "pilot_tests.h"

const unit_test plugin_tests[] = {
    {"lib_angle_wrap", lib_angle_wrap},
    {"lib_clamp_and_slew", lib_clamp_and_slew},
    {"lib_lowpass", lib_lowpass},
    {"lib_pid_step_response", lib_pid_step_response},
    {"lib_pid_saturation", lib_pid_saturation},
    {"lib_pid_anti_windup", lib_pid_anti_windup},
    {"lib_pid_slew_limit", lib_pid_slew_limit},
    {"lib_pid_integral_zone", lib_pid_integral_zone},
    {"lib_pid_bad_input", lib_pid_bad_input},
    {"lib_pid_config_check", lib_pid_config_check},
    {"pilot_param_errors", pilot_param_errors},
    {"pilot_heading_wraps_at_north", pilot_heading_wraps_at_north},
    {"pilot_heading_limits_and_slew", pilot_heading_limits_and_slew},
    {"pilot_heading_turn_rate_limit", pilot_heading_turn_rate_limit},
    {"pilot_heading_trim_integrator", pilot_heading_trim_integrator},
    {"pilot_depth_cascade_signs", pilot_depth_cascade_signs},
    {"pilot_depth_anti_windup", pilot_depth_anti_windup},
    {"pilot_depth_pitch_slew", pilot_depth_pitch_slew},
    {"pilot_pitch_control", pilot_pitch_control},
    {"pilot_altitude_target_and_search", pilot_altitude_target_and_search},
    {"pilot_speed_feed_forward_and_stop", pilot_speed_feed_forward_and_stop},
    {"pilot_rpm_limits", pilot_rpm_limits},
    {"pilot_bad_rpm_limits_fail_at_start", pilot_bad_rpm_limits_fail_at_start},
    {"pilot_speed_through_the_water", pilot_speed_through_the_water},
    {"pilot_setpoint_watch_counts_ignored", pilot_setpoint_watch_counts_ignored},
    {NULL, NULL},
};
