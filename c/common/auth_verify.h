/* Verifying a signed command (docs/security.md): the key by its id, the
 * MAC over the message's encoding with mac_len 0, then its counter (the
 * signer's clock in microseconds): within AUTH_STALE_US of this host's
 * clock, and above the newest accepted from the same (key id, sender).
 * The newest counters are kept in memory only, in a bounded table: after a
 * restart the staleness bound is what stops a replay of older commands. */
#ifndef AUV_AUTH_VERIFY_H
#define AUV_AUTH_VERIFY_H

#include <stddef.h>
#include <stdint.h>

#include "common/auth_keys.h"
#include "common/auth_mac.h"

#define AUTH_STALE_US (300LL * 1000000LL) /* 5 min */
#define AUTH_MAX_PEERS 64                 /* senders remembered; the least recently heard goes */
#define AUTH_MAX_SENDER 64

typedef enum {
    AUTH_OK = 0,
    AUTH_UNSIGNED,    /* no key id or no MAC, while a key is configured */
    AUTH_UNKNOWN_KEY, /* key id not in the key file */
    AUTH_BAD_MAC,     /* MAC of another message or another key, or cut short */
    AUTH_REPLAY,      /* counter not above the newest accepted from its sender */
    AUTH_STALE,       /* counter more than AUTH_STALE_US from this host's clock */
    AUTH_N_RESULTS
} auth_result;

typedef struct {
    char key_id[AUTH_MAX_KEY_ID + 1];
    char sender[AUTH_MAX_SENDER + 1];
    int64_t counter;
    uint64_t heard; /* verifier's tick when last accepted: for eviction */
} auth_peer;

typedef struct {
    auth_keyring ring;
    auth_peer peers[AUTH_MAX_PEERS];
    size_t n_peers;
    uint64_t tick;
    uint64_t refused[AUTH_N_RESULTS]; /* per reason; [AUTH_OK] counts accepted */
} auth_verifier;

/* The fields of a command_auth_t, whatever message carries it. */
typedef struct {
    const char *key_id, *sender;
    int64_t counter;
    const uint8_t *mac;
    int mac_len;
} auth_fields;

/* v's ring must be loaded (auth_keys_load). body: the message encoded with
 * mac_len 0. now_us: this host's clock (CLOCK_REALTIME), not mission time.
 * Counts the result in v->refused. */
auth_result auth_verify(auth_verifier *v, const auth_fields *a, const void *body, size_t body_len, int64_t now_us);
/* A result's text for acks and logs ("bad MAC"), and its name for tools and
 * tests ("bad_mac": the keys of RESULT_TEXT in python/auvlcm/auth.py). */
const char *auth_result_text(auth_result r);
const char *auth_result_name(auth_result r);
/* Microseconds since the epoch (CLOCK_REALTIME). */
int64_t auth_now_us(void);

#endif
