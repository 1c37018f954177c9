/* The C unit tests of plugin team (listed in test_list.c). */
#ifndef TEAM_TESTS_H
#define TEAM_TESTS_H

void contacts_merge_repeated_looks(void);
void targets_merge_across_reporters(void);
void route_beats_nearest_neighbour(void);
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

#endif
