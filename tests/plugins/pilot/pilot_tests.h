/* The pilot plugin's C unit tests (run one: test_plugin_pilot --plugins DIR NAME). */
#ifndef PILOT_TESTS_H
#define PILOT_TESTS_H

void lib_angle_wrap(void);
void lib_clamp_and_slew(void);
void lib_lowpass(void);
void lib_pid_step_response(void);
void lib_pid_saturation(void);
void lib_pid_anti_windup(void);
void lib_pid_slew_limit(void);
void lib_pid_integral_zone(void);
void lib_pid_bad_input(void);
void lib_pid_config_check(void);
void pilot_param_errors(void);
void pilot_heading_wraps_at_north(void);
void pilot_heading_limits_and_slew(void);
void pilot_heading_turn_rate_limit(void);
void pilot_heading_trim_integrator(void);
void pilot_depth_cascade_signs(void);
void pilot_depth_anti_windup(void);
void pilot_depth_pitch_slew(void);
void pilot_pitch_control(void);
void pilot_altitude_target_and_search(void);
void pilot_speed_feed_forward_and_stop(void);
void pilot_rpm_limits(void);
void pilot_bad_rpm_limits_fail_at_start(void);
void pilot_speed_through_the_water(void);
void pilot_setpoint_watch_counts_ignored(void);

#endif
