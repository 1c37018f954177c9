/* The team plugin's store: what one vehicle knows about its team, shared by
 * the plugin's behaviors in one manager (one manager runs one plan, so one
 * store per process). team_link owns the link and the event output (the
 * one-writer rule); the other behaviors read and update the store and queue
 * events that team_link posts.
 *
 * team_link's start() configures the store; it is cleared when the roster or
 * `me` differ from the last configuration or when time went backwards (a new
 * mission in the same process), and kept when team_link's state is entered
 * again, so contacts and progress survive a re-entry. */
#ifndef TM_STORE_H
#define TM_STORE_H

#include <stdint.h>

#include "chasm/chasm_plugin.h"
#include "tm_contacts.h"
#include "tm_front_rule.h"
#include "tm_keepclear.h"
#include "tm_lines.h"
#include "tm_outbox.h"
#include "tm_targets.h"
#include "team/team_codec.h"

/* status.state codes (the link schema's `state` field) */
enum { TM_ST_TRANSIT = 0, TM_ST_SURVEY = 1, TM_ST_TAKEOVER = 2, TM_ST_REACQUIRE = 3, TM_ST_DONE = 4, TM_ST_ABORT = 5 };

typedef struct {
    int heard;            /* any frame heard from it */
    double t_heard;       /* mission time of the last frame [s] */
    int has_status;
    double t_status;      /* the status's own time [s] */
    tm_track track;       /* position, course, speed at t_status */
    double depth;
    int next_line, state;
    int lost;             /* decided lost (sticky) */
    int dealt;            /* its lines dealt by the takeover rule */
} tm_peer;

typedef struct {
    int64_t utime;
    int kind;             /* team_event_t kind */
    int origin;           /* team index, -1 none */
    int number;
    double n, e;
    int result;
    char text[200];
} tm_event;

typedef struct {
    tm_key key;
    int result;
    double n, e, t;
} tm_ident;

#define TM_MAX_EVENTS 128

typedef struct {
    int configured;
    tm_roster roster;
    int me;
    int64_t last_now_us;
    double t_start;       /* when team_link started [s] */
    tm_peer peer[TM_MAX_TEAM];
    /* own search data */
    tm_contact_list contacts;
    tm_outbox out;
    /* targets heard (everyone keeps them; the RI vehicle acts on them) */
    tm_target_queue targets;
    int is_ri;
    double merge_m;       /* reports within this distance are one target (ri_reacquire's merge) */
    int targets_changed;  /* a target appeared: the RI vehicle replans */
    tm_ident idents[TM_MAX_IDENTS];   /* own results (RI), indexed like out.ident_sends */
    tm_key idents_heard[TM_MAX_IDENTS];
    int n_idents_heard;
    /* own status */
    int state;            /* TM_ST_* as set by the behaviors */
    int next_line;        /* index into own work list (tm_lines.h): the line flown now or next */
    double depth_offset;  /* keep_clear's offset, added by the steering behaviors [m] */
    tm_track own;         /* own navigation at the last team_status run */
    double own_depth;
    double t_own;         /* when [s] */
    int status_state;     /* the state code sent (team_status's `state`, or `state` above) */
    /* own front summary (team_link's `front` input, sampling) */
    team_msg_front own_front;
    int has_own_front;
    long fronts_made, fronts_not_sendable, fronts_sent, fronts_heard;
    tm_fr_looks looks;    /* front_rule's record of where the team looked */
    /* takeover: every vehicle's work list, kept by the rule (tm_lines.h) */
    tm_work work;
    int work_ready;
    /* events waiting for team_link */
    tm_event events[TM_MAX_EVENTS];
    int n_events;
    long events_dropped;
    int32_t seq;          /* of the frames sent */
    long frames_in, frames_sent, frames_bad, frames_foreign;
    long undecodable;     /* input messages (contacts, looks, frames) that did not decode */
} tm_store;

PU_HIDDEN tm_store *tm_store_get(void);
/* Configures (or keeps) the store for this roster and vehicle; see above. */
PU_HIDDEN void tm_store_configure(tm_store *s, const tm_roster *r, int me, int64_t now_us, int repeat);
/* The store if team_link configured it, else NULL with a log line that
 * says what is missing (for start()). */
PU_HIDDEN tm_store *tm_store_for(chasm_ctx *c, const char *behavior);
PU_HIDDEN void tm_post(tm_store *s, int64_t now_us, int kind, int origin, int number, double n, double e, int result,
                        const char *text);
PU_HIDDEN const char *tm_name(const tm_store *s, int index);

/* team_event_t kinds (lcmtypes/team_event_t.lcm) */
enum { TM_EV_CONTACT_NEW = 1, TM_EV_CONTACT_SENT = 2, TM_EV_CONTACT_ACKED = 3, TM_EV_TARGET_QUEUED = 4,
       TM_EV_TARGET_IDENTIFIED = 5, TM_EV_TARGET_NOT_FOUND = 6, TM_EV_ROUTE = 7, TM_EV_PEER_LOST = 8,
       TM_EV_LINES_TAKEN = 9, TM_EV_KEEP_CLEAR = 10, TM_EV_IDENT_HEARD = 11 };

#endif
