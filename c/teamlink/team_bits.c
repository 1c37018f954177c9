#include "teamlink/team_bits.h"

#include <string.h>

void team_bits_writer(team_bits *b, uint8_t *buf, size_t nbytes)
{
    if (nbytes)
        memset(buf, 0, nbytes);
    b->in = buf;
    b->out = buf;
    b->nbits = 8 * nbytes;
    b->pos = 0;
}

void team_bits_reader(team_bits *b, const uint8_t *buf, size_t nbytes)
{
    b->in = buf;
    b->out = NULL;
    b->nbits = 8 * nbytes;
    b->pos = 0;
}

size_t team_bits_left(const team_bits *b) { return b->nbits - b->pos; }

size_t team_bits_bytes(const team_bits *b) { return (b->pos + 7) / 8; }

int team_bits_put(team_bits *b, uint32_t value, unsigned bits)
{
    if (!b->out || bits > 32 || bits > team_bits_left(b))
        return -1;
    for (unsigned i = bits; i-- > 0; b->pos++) {
        uint8_t mask = (uint8_t)(0x80u >> (b->pos % 8));
        if ((value >> i) & 1u)
            b->out[b->pos / 8] |= mask;
        else
            b->out[b->pos / 8] &= (uint8_t)~mask;
    }
    return 0;
}

int team_bits_get(team_bits *b, unsigned bits, uint32_t *value)
{
    if (bits > 32 || bits > team_bits_left(b))
        return -1;
    uint32_t v = 0;
    for (unsigned i = 0; i < bits; i++, b->pos++)
        v = (v << 1) | ((b->in[b->pos / 8] >> (7 - b->pos % 8)) & 1u);
    *value = v;
    return 0;
}
