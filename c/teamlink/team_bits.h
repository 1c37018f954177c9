/* Bit writer and reader of the team-link codec (docs/modem.md).
 *
 * Values go most significant bit first, back to back, with no alignment: a
 * frame is as short as its fields allow. The generated codec
 * (build/gen/team/team_codec.c) is the only intended user; it checks room and
 * ranges before it writes, so a refused message never leaves half a message
 * behind. */
#ifndef TEAM_BITS_H
#define TEAM_BITS_H

#include <stddef.h>
#include <stdint.h>

typedef struct team_bits {
    const uint8_t *in; /* the frame read (the same bytes as out while writing) */
    uint8_t *out;      /* the frame written; NULL for a reader */
    size_t nbits;      /* size of the frame in bits */
    size_t pos;        /* next bit to read or write */
} team_bits;

/* A writer over buf[0..nbytes); buf is zeroed, so padding bits are zero. */
void team_bits_writer(team_bits *b, uint8_t *buf, size_t nbytes);
/* A reader over the frame buf[0..nbytes). */
void team_bits_reader(team_bits *b, const uint8_t *buf, size_t nbytes);

/* Bits not yet read or written. */
size_t team_bits_left(const team_bits *b);
/* Whole bytes holding what was written so far (the frame's length). */
size_t team_bits_bytes(const team_bits *b);

/* Write the low `bits` (0..32) bits of value: 0, or -1 (nothing written) if
 * they do not fit or this is a reader. */
int team_bits_put(team_bits *b, uint32_t value, unsigned bits);
/* Read `bits` (0..32) bits into *value: 0, or -1 (nothing read) if fewer are left. */
int team_bits_get(team_bits *b, unsigned bits, uint32_t *value);

#endif
