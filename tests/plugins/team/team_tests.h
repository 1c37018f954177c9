/* The C unit tests of plugin team (listed in test_list.c). */
#ifndef TEAM_TESTS_H
#define TEAM_TESTS_H

void contacts_merge_repeated_looks(void);
void targets_merge_across_reporters(void);
void route_beats_nearest_neighbour(void);
void ident_error_bounds_wrong_calls(void);
void route_is_deterministic(void);
void roster_and_lines_parse(void);
void takeover_round_robin_in_line_order(void);
void tdma_slots_from_the_clock(void);
void outbox_priorities(void);
void reports_survive_30_percent_loss(void);
void keep_clear_cpa(void);
void frames_carry_contacts_acks_and_status(void);
void repeats_are_acked_again_and_merged_once(void);
void hostile_frames_are_counted(void);
void time_stamps_unwrap(void);
void front_rule_picks_the_least_certain_place(void);
void frames_carry_the_front_summary(void);
void plan_refuses_bad_roster_and_lines(void);
void search_vehicle_reports_until_acked(void);
void ri_vehicle_merges_routes_and_identifies(void);
void ri_vehicle_passes_through_a_target_inside_its_turning_circle(void);
void lost_teammates_lines_are_taken(void);
void done_teammates_take_no_lines(void);
void aborted_teammate_is_lost_at_once(void);
void keep_clear_gives_way_in_depth(void);
void out_of_range_values_are_refused_and_logged(void);
void abort_state_keeps_the_store_and_says_abort(void);

#endif
