/* NMEA 0183 framing and fields, for every driver whose device speaks it (GPS,
 * compass/AHRS, the WHOI Micro-Modem) and for the replay of their raw bytes.
 * No LCM, no I/O, no allocation: bytes in, checked sentences out.
 *
 * A sentence is `$` (or `!`), an address field (talker + type, e.g. GPGGA, or a
 * proprietary P... address), comma-separated fields, `*hh` (the XOR of every
 * byte between the `$` and the `*`, in hex) and CR LF. The framer takes a
 * stream of any bytes: it skips what is not a sentence (counted as garbage),
 * refuses a line longer than NMEA_MAX_SENTENCE (an endless line cannot grow a
 * buffer), a line with a byte outside printable ASCII, a bad or missing
 * checksum, and a sentence cut short by a new `$` (truncated). Each refusal
 * has a reason, which the drivers count.
 *
 * Real receivers bend the framing in ways the standard allows or that carry
 * no doubt, and those are accepted: a line ended by CR LF, LF alone or CR
 * alone; a checksum in lower-case hex; a complete sentence (its `*hh`
 * present) followed at once by the next `$` with no line end between (some
 * receivers drop the CR LF when their output buffer is full): the first is
 * parsed, the second begins. The checksum is optional in NMEA 0183 for most
 * sentences (mandatory in RMA, RMB and RMC since version 2.0): a framer made
 * with allow_no_checksum accepts a line without one and marks it
 * (nmea_sentence.checksummed = 0) so that a driver refuses it where the
 * sentence's definition requires one.
 *
 * NMEA 0183 limits a sentence to 82 characters; proprietary ones run longer:
 * a Micro-Modem $CARXD of a PSK rate carries a 256-byte frame as 512 hex
 * digits (c/drivers/modem/mm_msg.h), some 540 characters in all, hence 600. */
#ifndef DRIVERS_NMEA_H
#define DRIVERS_NMEA_H

#include <stddef.h>
#include <stdint.h>

#define NMEA_MAX_SENTENCE 600
#define NMEA_MAX_FIELDS 80

typedef enum {
    NMEA_OK = 0,
    NMEA_BAD_CHECKSUM,  /* *hh present and wrong */
    NMEA_NO_CHECKSUM,   /* no *hh (refused unless the framer allows it) */
    NMEA_TOO_LONG,      /* over NMEA_MAX_SENTENCE before the line ended */
    NMEA_BAD_CHAR,      /* a byte outside printable ASCII inside a sentence */
    NMEA_TRUNCATED,     /* a new '$' (or '!') before the line ended */
    NMEA_BAD_ADDRESS,   /* the address field is not 5 letters/digits (or a P... proprietary one) */
    NMEA_TOO_MANY_FIELDS,
    NMEA_RESULT_COUNT
} nmea_result;

/* The reason of a refusal, as the drivers count it ("bad checksum", ...). */
const char *nmea_result_name(nmea_result r);

typedef struct {
    char talker[3];   /* "GP", "GN", "HC", "CC", "CA", ...; "" for a proprietary sentence */
    char type[16];    /* "GGA", "HDT", "RXD"; for a proprietary sentence its whole address ("PASHR") */
    int nfields;      /* fields after the address */
    int checksummed;  /* it carried *hh (and it matched); 0: none, allowed by the framer */
    const char *field[NMEA_MAX_FIELDS]; /* each NUL-terminated, "" when empty */
    char text[NMEA_MAX_SENTENCE + 1];   /* the sentence as received, without CR LF */
    char storage[NMEA_MAX_SENTENCE + 1];
} nmea_sentence;

typedef struct {
    char buf[NMEA_MAX_SENTENCE + 1];
    size_t len;
    int in_sentence;     /* between a '$' and the end of its line */
    int skipping;        /* a refused line: ignore bytes up to its end */
    int allow_no_checksum;
    uint64_t garbage_bytes; /* bytes outside any sentence (not CR/LF) */
} nmea_framer;

void nmea_framer_init(nmea_framer *f, int allow_no_checksum);

/* One byte of the stream. Returns NMEA_OK with *out filled when a sentence
 * ended (at a line end, or at the `$` that follows its *hh at once) and
 * passed every check; a refusal reason when a line was refused; -1 when
 * neither happened with this byte. */
int nmea_framer_push(nmea_framer *f, uint8_t byte, nmea_sentence *out);

/* Checks and splits one line ("$...*hh", CR LF optional) into *out. */
nmea_result nmea_parse_line(const char *line, size_t len, int allow_no_checksum, nmea_sentence *out);

/* The checksum of body (the bytes between '$' and '*'). */
uint8_t nmea_checksum(const char *body, size_t len);

/* "$" body "*hh\r\n" into out (size n); returns its length, or -1 if it does not fit. */
int nmea_format(char *out, size_t n, const char *body);

/* ---- fields. Each returns 1 and sets *out for a well-formed, in-range value,
 * 0 for an empty field (no value), -1 for a malformed or out-of-range one. */
int nmea_field_double(const nmea_sentence *s, int i, double *out);
int nmea_field_int(const nmea_sentence *s, int i, long *out);
/* ddmm.mmmm (latitude) or dddmm.mmmm (longitude) and its hemisphere field
 * (N/S, E/W) into signed degrees: minutes < 60, |lat| <= 90, |lon| <= 180. */
int nmea_field_latitude(const nmea_sentence *s, int i, double *deg);
int nmea_field_longitude(const nmea_sentence *s, int i, double *deg);
/* hhmmss(.ss) into seconds of the day [0, 86400] (a leap second allowed). */
int nmea_field_time_of_day(const nmea_sentence *s, int i, double *seconds);
/* ddmmyy (RMC) into a Unix day number; years 80-99 are 19xx, 00-79 20xx. */
int nmea_field_date_ddmmyy(const nmea_sentence *s, int i, int64_t *unix_day);
/* Day number since 1970-01-01 of a calendar date, or -1 if it is not one. */
int64_t nmea_unix_day(int year, int month, int day);

#endif
