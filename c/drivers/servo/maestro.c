/* The Maestro's serial protocol, host side (maestro.h): command encoders and
 * the reply decoder. */
#include "drivers/servo/maestro.h"

#include <string.h>

/* The command byte, in the compact or the Pololu form; returns its length
 * (1 or 3) or 0 when the device number does not fit 7 bits. */
static size_t header(const maestro_framing *f, uint8_t *out, uint8_t cmd)
{
    if (!f->pololu) {
        out[0] = cmd;
        return 1;
    }
    if (f->device > 127)
        return 0;
    out[0] = MAESTRO_POLOLU_START;
    out[1] = f->device;
    out[2] = (uint8_t)(cmd & 0x7F); /* the Pololu form clears the command's MSB */
    return 3;
}

/* A 14-bit number as two data bytes, low 7 bits first. */
static size_t put14(uint8_t *out, unsigned v)
{
    out[0] = (uint8_t)(v & 0x7F);
    out[1] = (uint8_t)((v >> 7) & 0x7F);
    return 2;
}

/* A command of one channel and one 14-bit number (targets, speeds, accelerations). */
static size_t channel_value(const maestro_framing *f, uint8_t *out, uint8_t cmd, unsigned channel, unsigned v,
                            unsigned vmax)
{
    if (channel >= MAESTRO_MAX_CHANNELS || v > vmax)
        return 0;
    size_t n = header(f, out, cmd);
    if (!n)
        return 0;
    out[n++] = (uint8_t)channel;
    return n + put14(out + n, v);
}

size_t maestro_set_target(const maestro_framing *f, uint8_t *out, unsigned channel, unsigned target_qus)
{
    return channel_value(f, out, MAESTRO_SET_TARGET, channel, target_qus, MAESTRO_MAX_TARGET);
}

size_t maestro_set_speed(const maestro_framing *f, uint8_t *out, unsigned channel, unsigned speed)
{
    return channel_value(f, out, MAESTRO_SET_SPEED, channel, speed, MAESTRO_MAX_SPEED);
}

size_t maestro_set_acceleration(const maestro_framing *f, uint8_t *out, unsigned channel, unsigned accel)
{
    return channel_value(f, out, MAESTRO_SET_ACCELERATION, channel, accel, MAESTRO_MAX_ACCELERATION);
}

size_t maestro_set_multiple_targets(const maestro_framing *f, uint8_t *out, unsigned first, unsigned n,
                                    const uint16_t *targets_qus)
{
    if (n < 1 || first >= MAESTRO_MAX_CHANNELS || n > MAESTRO_MAX_CHANNELS - first)
        return 0;
    for (unsigned i = 0; i < n; i++)
        if (targets_qus[i] > MAESTRO_MAX_TARGET)
            return 0;
    size_t len = header(f, out, MAESTRO_SET_MULTIPLE_TARGETS);
    if (!len)
        return 0;
    out[len++] = (uint8_t)n;
    out[len++] = (uint8_t)first;
    for (unsigned i = 0; i < n; i++)
        len += put14(out + len, targets_qus[i]);
    return len;
}

size_t maestro_get_position(const maestro_framing *f, uint8_t *out, unsigned channel)
{
    if (channel >= MAESTRO_MAX_CHANNELS)
        return 0;
    size_t n = header(f, out, MAESTRO_GET_POSITION);
    if (!n)
        return 0;
    out[n++] = (uint8_t)channel;
    return n;
}

size_t maestro_get_moving_state(const maestro_framing *f, uint8_t *out)
{
    return header(f, out, MAESTRO_GET_MOVING_STATE);
}

size_t maestro_get_errors(const maestro_framing *f, uint8_t *out) { return header(f, out, MAESTRO_GET_ERRORS); }

size_t maestro_go_home(const maestro_framing *f, uint8_t *out) { return header(f, out, MAESTRO_GO_HOME); }

size_t maestro_baud_indication(const maestro_framing *f, uint8_t *out)
{
    maestro_framing pololu = {1, f->pololu ? f->device : MAESTRO_DEFAULT_DEVICE};
    return header(&pololu, out, MAESTRO_GET_ERRORS);
}

const char *maestro_error_name(unsigned bit)
{
    static const char *const names[] = {
        "serial signal error", "serial overrun error", "serial buffer full", "serial CRC error",
        "serial protocol error", "serial timeout error", "script stack error", "script call stack error",
        "script program counter error",
    };
    return bit < sizeof names / sizeof names[0] ? names[bit] : NULL;
}

const char *maestro_rx_result_name(maestro_rx_result r)
{
    static const char *const names[MRX_N_RESULTS] = {
        "none", "position", "errors", "moving state", "unexpected byte", "position out of range",
        "undefined error bits", "bad moving state", "reply timeout", "too many queries waiting",
    };
    return (unsigned)r < MRX_N_RESULTS ? names[r] : "?";
}

/* ------------------------------------------------------------ replies */

void maestro_rx_init(maestro_rx *rx) { memset(rx, 0, sizeof *rx); }

maestro_rx_result maestro_rx_expect(maestro_rx *rx, maestro_query q, unsigned channel)
{
    if (rx->count == MAESTRO_RX_PENDING) {
        rx->refused[MRX_QUEUE_FULL]++;
        return MRX_QUEUE_FULL;
    }
    unsigned at = (rx->head + rx->count) % MAESTRO_RX_PENDING;
    rx->query[at] = (uint8_t)q;
    rx->channel[at] = (uint8_t)channel;
    rx->count++;
    return MRX_NONE;
}

/* The reply at the head is complete (or refused): the next query is awaited. */
static void pop(maestro_rx *rx)
{
    rx->head = (rx->head + 1) % MAESTRO_RX_PENDING;
    rx->count--;
    rx->have = 0;
}

static maestro_rx_result refuse(maestro_rx *rx, maestro_rx_result r, unsigned bytes)
{
    rx->refused[r]++;
    rx->refused_bytes += bytes;
    return r;
}

maestro_rx_result maestro_rx_push(maestro_rx *rx, uint8_t byte, maestro_rx_event *ev)
{
    ev->kind = MRX_NONE;
    ev->channel = 0;
    ev->value = 0;
    if (!rx->count)
        return ev->kind = refuse(rx, MRX_UNEXPECTED, 1);
    maestro_query q = (maestro_query)rx->query[rx->head];
    rx->part[rx->have++] = byte;
    if (q == MAESTRO_Q_MOVING) {
        pop(rx);
        if (byte > 1)
            return ev->kind = refuse(rx, MRX_BAD_MOVING, 1);
        rx->replies++;
        ev->value = byte;
        return ev->kind = MRX_MOVING;
    }
    if (rx->have < 2)
        return MRX_NONE;
    /* two full 8-bit bytes, low first (unlike the commands' 7-bit data bytes) */
    unsigned v = (unsigned)rx->part[0] | (unsigned)rx->part[1] << 8;
    unsigned channel = rx->channel[rx->head];
    pop(rx);
    if (q == MAESTRO_Q_POSITION && v > MAESTRO_MAX_TARGET)
        return ev->kind = refuse(rx, MRX_BAD_POSITION, 2);
    if (q == MAESTRO_Q_ERRORS && (v & ~MAESTRO_ERR_DEFINED))
        return ev->kind = refuse(rx, MRX_BAD_ERRORS, 2);
    rx->replies++;
    ev->value = v;
    ev->channel = channel;
    return ev->kind = q == MAESTRO_Q_POSITION ? MRX_POSITION : MRX_ERRORS;
}

unsigned maestro_rx_timeout(maestro_rx *rx)
{
    unsigned n = rx->count;
    rx->refused[MRX_TIMEOUT] += n;
    rx->refused_bytes += rx->have;
    rx->count = 0;
    rx->have = 0;
    return n;
}
