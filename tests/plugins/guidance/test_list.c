/* The list the harness runs (tests/plugins/common/plugin_test.h). */
#include "gd_tests.h"

const unit_test plugin_tests[] = {
    {"line_frame", line_frame},
    {"los_heading_wraps", los_heading_wraps},
    {"los_cross_track_decays", los_cross_track_decays},
    {"ilos_removes_the_current_offset", ilos_removes_the_current_offset},
    {"circle_following", circle_following},
    {"survey_lines_box", survey_lines_box},
    {"survey_lines_polygon", survey_lines_polygon},
    {"parameter_errors", parameter_errors},
    {"goto_reaches_the_waypoint_on_the_line", goto_reaches_the_waypoint_on_the_line},
    {"track_is_done_past_its_end", track_is_done_past_its_end},
    {"lawnmower_flies_every_line", lawnmower_flies_every_line},
    {"lawnmower_resume_continues_the_line", lawnmower_resume_continues_the_line},
    {"lawnmower_polygon_and_progress_at_entry", lawnmower_polygon_and_progress_at_entry},
    {"bad_combinations_fail_at_entry", bad_combinations_fail_at_entry},
    {"timer_is_done_after_its_duration", timer_is_done_after_its_duration},
    {"surface_fix_times_out_as_failed", surface_fix_times_out_as_failed},
    {"surface_fix_needs_a_new_fix", surface_fix_needs_a_new_fix},
    {"surface_floats_up", surface_floats_up},
    {"yoyo_stays_in_its_band", yoyo_stays_in_its_band},
    {"yoyo_rate_floor_and_profiles", yoyo_rate_floor_and_profiles},
    {"holds_and_speed", holds_and_speed},
    {"loiter_circles_the_point", loiter_circles_the_point},
    {NULL, NULL},
};
