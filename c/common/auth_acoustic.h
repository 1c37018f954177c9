/* The acoustic link's command frames (docs/security.md, "Acoustic"): a
 * 32-bit tag, HMAC-SHA-256 truncated, over a frame's payload and a 24-bit
 * counter, and a receiver's replay window. The frame layout itself belongs
 * to the team link (c/plugins/team/team_link.schema), not to this file. */
#ifndef AUV_AUTH_ACOUSTIC_H
#define AUV_AUTH_ACOUSTIC_H

#include <stddef.h>
#include <stdint.h>

/* The acoustic frame tag: the first 4 bytes, big-endian, of
 * HMAC-SHA-256(key, "CHASM-ACOUSTIC-1" || counter (3 bytes, big-endian) || payload),
 * the counter's low 24 bits only. 0 and the tag in *tag, or -1 when the payload
 * is over AUTH_ACOUSTIC_MAX_PAYLOAD bytes (a frame is 32) or libcrypto fails. */
#define AUTH_ACOUSTIC_MAX_PAYLOAD 256
int auth_acoustic_tag(const uint8_t *key, size_t key_len, const void *payload, size_t len, uint32_t counter24,
                      uint32_t *tag);


#define AUTH_ACOUSTIC_WINDOW 32

/* The newest counter accepted and which of the 32 below it were seen:
 * frames relayed out of order still pass, each once. Zero it to start. */
typedef struct {
    int64_t newest; /* -1 before the first frame: set by auth_acoustic_init */
    uint32_t seen;  /* bit i: counter newest - i accepted */
} auth_acoustic_window;

void auth_acoustic_init(auth_acoustic_window *w);
/* 0 accepted (and remembered), 1 bad tag, 2 replay, 3 too old (below the window). */
int auth_acoustic_verify(auth_acoustic_window *w, const uint8_t *key, size_t key_len, const void *payload,
                         size_t len, uint32_t counter24, uint32_t tag);

#endif
