/* Every C unit test of plugin team, run by name by tests/plugins/test_plugins_unit.py. */
#include "../common/plugin_test.h"
#include "team_tests.h"

const unit_test plugin_tests[] = {
    {"contacts_merge_repeated_looks", contacts_merge_repeated_looks},
    {"targets_merge_across_reporters", targets_merge_across_reporters},
    {"route_beats_nearest_neighbour", route_beats_nearest_neighbour},
    {"ident_error_bounds_wrong_calls", ident_error_bounds_wrong_calls},
    {"route_is_deterministic", route_is_deterministic},
    {"roster_and_lines_parse", roster_and_lines_parse},
    {"takeover_round_robin_in_line_order", takeover_round_robin_in_line_order},
    {"tdma_slots_from_the_clock", tdma_slots_from_the_clock},
    {"outbox_priorities", outbox_priorities},
    {"reports_survive_30_percent_loss", reports_survive_30_percent_loss},
    {"keep_clear_cpa", keep_clear_cpa},
    {"frames_carry_contacts_acks_and_status", frames_carry_contacts_acks_and_status},
    {"repeats_are_acked_again_and_merged_once", repeats_are_acked_again_and_merged_once},
    {"hostile_frames_are_counted", hostile_frames_are_counted},
    {"time_stamps_unwrap", time_stamps_unwrap},
    {"frames_carry_the_front_summary", frames_carry_the_front_summary},
    {"plan_refuses_bad_roster_and_lines", plan_refuses_bad_roster_and_lines},
    {"search_vehicle_reports_until_acked", search_vehicle_reports_until_acked},
    {"ri_vehicle_merges_routes_and_identifies", ri_vehicle_merges_routes_and_identifies},
    {"ri_vehicle_passes_through_a_target_inside_its_turning_circle",
     ri_vehicle_passes_through_a_target_inside_its_turning_circle},
    {"lost_teammates_lines_are_taken", lost_teammates_lines_are_taken},
    {"done_teammates_take_no_lines", done_teammates_take_no_lines},
    {"aborted_teammate_is_lost_at_once", aborted_teammate_is_lost_at_once},
    {"keep_clear_gives_way_in_depth", keep_clear_gives_way_in_depth},
    {"out_of_range_values_are_refused_and_logged", out_of_range_values_are_refused_and_logged},
    {"abort_state_keeps_the_store_and_says_abort", abort_state_keeps_the_store_and_says_abort},
    {NULL, NULL},
};
