/* The lockstep clock's board of reports, kept in C.
 *
 * Why: the launcher's clock hears every participant's STEP_DONE of every step
 * (four or five per vehicle per step): 560 000 reports in an 8-vehicle survey.
 * Decoding and tracking each one in Python was half of the launcher's CPU.
 * Nearly all of them say one thing, "participant P finished step n, the next
 * one it owed": the board takes exactly those off the clock's own socket
 * (common/lcm_udpm_reader.h) and raises P's last step done, in arrival order,
 * without waking Python for each one. Everything else (a registration, a
 * leave, a repeat of an older step, a step beyond the limit, an unknown
 * participant, a message that does not decode exactly) is handed to Python
 * as before, whose tracker (python/sim/multihil/lockstep.py) stays the one
 * that decides: it tells the board whom it knows and what each has done.
 *
 * The board answers the clock's only question, "who still owes step n",
 * from the same table. */
#ifndef AUV_LOCKSTEP_BOARD_H
#define AUV_LOCKSTEP_BOARD_H

#include <stdint.h>

#include "lcm_udpm_reader.h"

typedef struct lockstep_board lockstep_board_t;

#define LOCKSTEP_BOARD_UNKNOWN INT64_MIN

/* A board for the lockstep reports on channel, whose lockstep_t packed
 * fingerprint is fingerprint (as lcm-gen computes it). NULL when out of memory. */
lockstep_board_t *lockstep_board_new(const char *channel, uint64_t fingerprint);
void lockstep_board_free(lockstep_board_t *b);

/* Adds a participant, or sets its last step done. 0, or -1 out of memory. */
int lockstep_board_put(lockstep_board_t *b, const char *name, int64_t last_done);
void lockstep_board_remove(lockstep_board_t *b, const char *name);
/* A participant's last step done; LOCKSTEP_BOARD_UNKNOWN if not on the board. */
int64_t lockstep_board_last_done(const lockstep_board_t *b, const char *name);

/* The board takes a report of a step no later than limit (the step the clock
 * published last, plus one); later ones go to Python, which counts them. */
void lockstep_board_set_limit(lockstep_board_t *b, int64_t limit);

/* The step the clock waits for: lockstep_board_next says when the board took
 * the last report it owed (nobody on the board owes it any more). */
void lockstep_board_set_watch(lockstep_board_t *b, int64_t step);

/* How many participants have not reported step yet. */
int lockstep_board_owing(const lockstep_board_t *b, int64_t step);
/* The i-th participant that owes step (0-based, in the order they were put),
 * copied to out: 1, or 0 past the end. */
int lockstep_board_owing_at(const lockstep_board_t *b, int64_t step, int i, char *out, int out_len);

/* Reports the board took itself since it was made. */
int64_t lockstep_board_taken(const lockstep_board_t *b);

/* 1 when the message is a STEP_DONE the board took (a known participant's
 * first report of a step in (last done, limit]), else 0: the caller hands it on. */
int lockstep_board_take(lockstep_board_t *b, const char *channel, const void *data, int len);

/* lcm_udpm_reader_next that lets the board take its reports first: 1 (a
 * message in m for the caller), 0 nothing else queued, -1 on a receive error,
 * or 2 when nothing else is queued and a report the board took completed the
 * watched step (the clock may advance). */
int lockstep_board_next(lockstep_board_t *b, lcm_udpm_reader_t *r, lcm_udpm_msg *m);

/* lockstep_board_next that sleeps on the socket until it returns 1, 2 or -1,
 * or until timeout_ms passed or a signal came (0). The reports that do not
 * complete the step wake only this loop, never the caller's: in an 8-vehicle
 * run, five wake-ups of the clock's Python in six. */
int lockstep_board_wait(lockstep_board_t *b, lcm_udpm_reader_t *r, lcm_udpm_msg *m, int timeout_ms);

#endif
