/* Team key files (docs/security.md, "Keys"): written by auv-keygen, mode
 * 0600, one key a line "KEY_ID HEX_SECRET" ('#' comments, blank lines
 * ignored). Every key verifies; the last one signs, so a file holding the
 * old and the new key during a rotation accepts both. */
#ifndef AUV_AUTH_KEYS_H
#define AUV_AUTH_KEYS_H

#include <stddef.h>
#include <stdint.h>

#define AUTH_MAX_KEYS 4
#define AUTH_MAX_KEY_ID 32
#define AUTH_MIN_SECRET 16
#define AUTH_MAX_SECRET 64

typedef struct {
    char id[AUTH_MAX_KEY_ID + 1];
    uint8_t secret[AUTH_MAX_SECRET];
    size_t len;
} auth_key;

typedef struct {
    auth_key keys[AUTH_MAX_KEYS];
    size_t n;
} auth_keyring;

/* Loads path into ring. The file must be a regular file no one but its
 * owner may read or write (mode 0600 or stricter). 0, or -1 with a
 * "path[:line]: reason" message in err. */
int auth_keys_load(const char *path, auth_keyring *ring, char *err, size_t err_len);
/* The key of that id, or NULL. */
const auth_key *auth_keys_find(const auth_keyring *ring, const char *id);
/* Wipes the secrets (OPENSSL_cleanse). */
void auth_keys_clear(auth_keyring *ring);

#endif
