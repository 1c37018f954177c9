/* The Pololu Maestro servo controller's serial protocol, host side: encoders
 * of the commands the fins-and-thruster driver sends, and a decoder of the
 * replies the device sends back. No LCM, no I/O, no allocation.
 *
 * Published in Pololu's "Maestro Servo Controller User's Guide" (serial
 * servo commands). Two framings of the same commands:
 *
 *   compact:  CMD (MSB set), data bytes (MSB clear)
 *   Pololu:   0xAA, device number, CMD with its MSB cleared, data bytes
 *
 * The Pololu form lets several devices share one line; each answers only its
 * own device number (12 unless configured). Numbers are sent as two 7-bit
 * data bytes, low bits first. Targets are in quarter-microseconds (1500 us is
 * 6000); 0 switches a channel's pulses off.
 *
 * Replies carry no framing at all: a Get Position is answered by two bytes
 * (the position, low byte first, 8 bits each), Get Errors by two bytes (the
 * error bits, low byte first, cleared by the read), Get Moving State by one
 * byte (0 or 1). So the decoder has to know which queries were sent, in
 * order: the driver tells it with maestro_rx_expect() when it writes one. A
 * byte that answers nothing, a reply that cannot be (a position beyond any
 * target, undefined error bits, a moving state of 7) and a reply cut off by
 * the driver's deadline are refused, each with its reason. */
#ifndef DRIVERS_MAESTRO_H
#define DRIVERS_MAESTRO_H

#include <stddef.h>
#include <stdint.h>

/* Command bytes (compact form). */
#define MAESTRO_SET_TARGET 0x84
#define MAESTRO_SET_SPEED 0x87
#define MAESTRO_SET_ACCELERATION 0x89
#define MAESTRO_GET_POSITION 0x90
#define MAESTRO_GET_MOVING_STATE 0x93
#define MAESTRO_SET_MULTIPLE_TARGETS 0x9F /* Mini Maestro 12, 18 and 24 only */
#define MAESTRO_GET_ERRORS 0xA1
#define MAESTRO_GO_HOME 0xA2
#define MAESTRO_POLOLU_START 0xAA

#define MAESTRO_DEFAULT_DEVICE 12
#define MAESTRO_MAX_CHANNELS 24     /* the Mini Maestro 24 */
#define MAESTRO_MAX_TARGET 16383    /* 14 bits: 4095.75 us */
#define MAESTRO_MAX_SPEED 16383     /* (0.25 us)/(10 ms); 0 = unlimited */
#define MAESTRO_MAX_ACCELERATION 255 /* (0.25 us)/(10 ms)/(80 ms); 0 = unlimited */
/* Room for any one command this file encodes: a Set Multiple Targets of
 * every channel in the Pololu form. */
#define MAESTRO_MAX_COMMAND (3 + 2 + 2 * MAESTRO_MAX_CHANNELS + 1)

/* Which framing, and the device number the Pololu form addresses. */
typedef struct {
    int pololu;     /* 0: compact protocol; 1: Pololu protocol */
    uint8_t device; /* 0..127, the Pololu form only */
} maestro_framing;

/* Encoders: each writes one command into out (at least MAESTRO_MAX_COMMAND
 * bytes) and returns its length, or 0 when an argument is out of the
 * protocol's range (channel past 23, target past 16383, device past 127):
 * nothing is written then. */
size_t maestro_set_target(const maestro_framing *f, uint8_t *out, unsigned channel, unsigned target_qus);
/* Consecutive channels first..first+n-1 (n >= 1) in one command. */
size_t maestro_set_multiple_targets(const maestro_framing *f, uint8_t *out, unsigned first, unsigned n,
                                    const uint16_t *targets_qus);
size_t maestro_set_speed(const maestro_framing *f, uint8_t *out, unsigned channel, unsigned speed);
size_t maestro_set_acceleration(const maestro_framing *f, uint8_t *out, unsigned channel, unsigned accel);
size_t maestro_get_position(const maestro_framing *f, uint8_t *out, unsigned channel);
size_t maestro_get_moving_state(const maestro_framing *f, uint8_t *out);
size_t maestro_get_errors(const maestro_framing *f, uint8_t *out);
size_t maestro_go_home(const maestro_framing *f, uint8_t *out);

/* The first bytes after opening the port, in either framing: a Maestro in its
 * default serial mode ("UART, detect baud rate") ignores every command until
 * it has seen the baud rate indication byte 0xAA, and takes that byte as the
 * start of a Pololu-protocol command. So it goes as a whole, harmless Pololu
 * command: Get Errors (AA, device, 21; device 12 under the compact framing,
 * whose table names none), answered by two bytes like any Get Errors (expect
 * them). A lone 0xAA before compact commands would be a command cut by the
 * next one: a serial protocol error. */
size_t maestro_baud_indication(const maestro_framing *f, uint8_t *out);

/* The error bits of Get Errors, as published. */
#define MAESTRO_ERR_SERIAL_SIGNAL (1u << 0)      /* a stop bit missing: baud rate or noise */
#define MAESTRO_ERR_SERIAL_OVERRUN (1u << 1)     /* the UART's own buffer overran */
#define MAESTRO_ERR_SERIAL_BUFFER_FULL (1u << 2) /* the firmware's receive buffer was full */
#define MAESTRO_ERR_SERIAL_CRC (1u << 3)         /* a bad CRC byte (CRC mode) */
#define MAESTRO_ERR_SERIAL_PROTOCOL (1u << 4)    /* a malformed or nonsensical command */
#define MAESTRO_ERR_SERIAL_TIMEOUT (1u << 5)     /* no command within the device's serial timeout */
#define MAESTRO_ERR_SCRIPT_STACK (1u << 6)
#define MAESTRO_ERR_SCRIPT_CALL_STACK (1u << 7)
#define MAESTRO_ERR_SCRIPT_PC (1u << 8)
#define MAESTRO_ERR_DEFINED 0x01FFu
/* "serial protocol error", ...; NULL for a bit with no published meaning. */
const char *maestro_error_name(unsigned bit);

/* ------------------------------------------------------------ replies */

typedef enum {
    MAESTRO_Q_POSITION = 0,
    MAESTRO_Q_ERRORS,
    MAESTRO_Q_MOVING,
} maestro_query;

typedef enum {
    MRX_NONE = 0,        /* nothing complete yet */
    MRX_POSITION,        /* ev.channel, ev.value: a position in quarter-us */
    MRX_ERRORS,          /* ev.value: the error bits */
    MRX_MOVING,          /* ev.value: 0 or 1 */
    /* refusals, each counted */
    MRX_UNEXPECTED,      /* a byte while no query was waiting for one */
    MRX_BAD_POSITION,    /* a position past MAESTRO_MAX_TARGET */
    MRX_BAD_ERRORS,      /* error bits without a published meaning */
    MRX_BAD_MOVING,      /* a moving state other than 0 or 1 */
    MRX_TIMEOUT,         /* no whole reply by the driver's deadline */
    MRX_QUEUE_FULL,      /* a query sent while MAESTRO_RX_PENDING were unanswered */
    MRX_N_RESULTS
} maestro_rx_result;

/* "unexpected byte", "position out of range", ... */
const char *maestro_rx_result_name(maestro_rx_result r);

#define MAESTRO_RX_PENDING 32

typedef struct {
    maestro_rx_result kind;
    unsigned channel; /* MRX_POSITION */
    unsigned value;
} maestro_rx_event;

typedef struct {
    uint8_t query[MAESTRO_RX_PENDING]; /* a ring of queries awaiting replies */
    uint8_t channel[MAESTRO_RX_PENDING];
    unsigned head, count;
    uint8_t part[2]; /* bytes of the reply under way */
    unsigned have;
    uint64_t refused[MRX_N_RESULTS];  /* per reason: refusals */
    uint64_t refused_bytes;           /* bytes in refused replies, and unexpected ones */
    uint64_t replies;                 /* accepted replies */
} maestro_rx;

void maestro_rx_init(maestro_rx *rx);
/* The driver wrote a query: its reply is next after those already awaited.
 * MRX_QUEUE_FULL (counted, the query forgotten) when too many are waiting. */
maestro_rx_result maestro_rx_expect(maestro_rx *rx, maestro_query q, unsigned channel);
/* One byte from the device. Returns the event it completes (MRX_NONE while a
 * reply is incomplete); a refusal is already counted when returned. */
maestro_rx_result maestro_rx_push(maestro_rx *rx, uint8_t byte, maestro_rx_event *ev);
/* The driver's reply deadline passed: every query still waiting is refused as
 * MRX_TIMEOUT (a part of a reply with it). Returns how many. */
unsigned maestro_rx_timeout(maestro_rx *rx);

#endif
