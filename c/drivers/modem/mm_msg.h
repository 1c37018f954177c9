/* The WHOI Micro-Modem's NMEA interface: the subset a team link uses
 * (Micro-Modem Software Interface Guide), both directions. No LCM, no I/O:
 * an nmea_sentence in, a checked message out; a message in, a sentence body
 * out (nmea_format() adds the '$' and the checksum).
 *
 * host -> modem                          modem -> host
 *   CCCFG,NAME,VALUE  set a parameter      CACFG,NAME,VALUE   a parameter's value
 *   CCCFQ,NAME        query one (ALL)      CACYC,CMD,ADR1,ADR2,RATE,ACK,NFRAMES
 *   CCCYC,CMD,ADR1,ADR2,RATE,ACK,NFRAMES   CADRQ,HHMMSS,SRC,DEST,ACK,N,F#
 *   CCTXD,SRC,DEST,ACK,HEX                 CATXD,SRC,DEST,ACK,N   (echo of CCTXD)
 *   CCMPC,SRC,DEST    ping                 CARXD,SRC,DEST,ACK,F#,HEX
 *                                          CAACK,SRC,DEST,F#[,ACK]
 *                                          CAERR,HHMMSS,MODULE,NUMBER,TEXT
 *                                          CAREV,HHMMSS,IDENT,VERSION
 *                                          CAXST,... and CACST,... (statistics)
 *
 * Frames are numbered from 1 (F#), addresses are 0..127 with 0 the broadcast
 * address, data is hex (two digits a byte; upper case written, either read).
 * ADR1 of a cycle is the modem that will send the data, ADR2 the one that
 * receives it. In CAACK, SRC is the modem that acknowledges (the data's
 * receiver) and DEST the one whose frame it acknowledges. */
#ifndef DRIVERS_MM_MSG_H
#define DRIVERS_MM_MSG_H

#include <stdint.h>

#include "drivers/common/nmea.h"

#define MM_MAX_RATE 5
#define MM_MAX_ADDRESS 127
#define MM_BROADCAST 0
#define MM_MAX_FRAME_BYTES 256   /* the largest frame of any rate */
#define MM_MAX_FRAMES 8          /* the most frames in a packet (rate 5) */
#define MM_BODY_MAX 560          /* the longest body: a CARXD with 256 bytes of hex */

/* Bytes in one frame, and frames in one packet, at a rate (packet type):
 * rate 0 FH-FSK 1 x 32; PSK rates 1 and 2: 3 x 64, 3 and 4: 2 x 256, 5: 8 x 256.
 * -1 for a rate the modem does not have. */
int mm_rate_frame_bytes(int rate);
int mm_rate_frames(int rate);

typedef enum {
    MM_NONE = 0,
    MM_CCCFG, MM_CCCFQ, MM_CCCYC, MM_CCTXD, MM_CCMPC,
    MM_CACFG, MM_CACYC, MM_CADRQ, MM_CATXD, MM_CARXD, MM_CAACK, MM_CAERR, MM_CAREV, MM_CAXST, MM_CACST,
    MM_KIND_COUNT
} mm_kind;

/* "CCCYC", ... ; "" for MM_NONE. */
const char *mm_kind_name(mm_kind k);

typedef struct {
    char name[32];   /* SRC, CST, ALL, ...; Micro-Modem 2: xst.version, ... */
    char value[48];  /* CCCFG and CACFG; "" in a CCCFQ */
} mm_cfg;

typedef struct {
    int cmd;      /* deprecated by the modem's makers; written 0 */
    int src;      /* ADR1: the modem that sends the data */
    int dest;     /* ADR2 */
    int rate;     /* the packet type, 0..5 */
    int ack;      /* 0 or 1 */
    int nframes;  /* 1..the rate's frames */
} mm_cyc;

typedef struct {
    double time_s;  /* HHMMSS as seconds of the day; -1 if the field is empty */
    int src, dest, ack;
    int nbytes;     /* the most bytes this frame can hold */
    int frame;      /* F#, from 1 */
} mm_drq;

typedef struct {
    int src, dest, ack;
    int frame;      /* F# (CARXD only; 0 elsewhere) */
    int n;          /* bytes of data (CATXD: its N field) */
    uint8_t data[MM_MAX_FRAME_BYTES];
} mm_data;

typedef struct {
    int src, dest, frame;
    int ack;        /* the optional fourth field; -1 absent */
} mm_ack;

typedef struct {
    double time_s;  /* -1 if empty */
    char module[16];
    int number;     /* -1 if the field is empty */
    char text[96];
} mm_err;

typedef struct {
    double time_s;  /* -1 if empty */
    char ident[16]; /* AUV (the firmware), INIT (it has just booted), COPROC, ... */
    char version[32];
} mm_rev;

/* Transmit statistics. Version 0 has no version field (its first field is a
 * YYYYMMDD date); version 6 puts 6 first and shifts the rest by one; the
 * later versions of Micro-Modem 2 firmware (7, 8) keep version 6's fields and
 * add theirs after them. Versions above MM_MAX_STAT_VERSION are refused. */
#define MM_MAX_STAT_VERSION 99
typedef struct {
    int version;
    int rate, src, dest, ack, nframes_expected, nframes_sent, packet_type, nbytes;
} mm_xst;

/* Cycle (receive) statistics; the same version rule (a first field of 6 or
 * more is the version, a smaller one is the mode of version 0). mode 0: good,
 * 1: bad CRC, 2: packet timeout. snr_in is the SNR at the receiver's input
 * (what modem_rx_t.snr_db reports). */
typedef struct {
    int version, mode;
    int rate, src, dest, packet_type, nframes, nbad;
    double snr_rss, snr_in, snr_out, snr_sym, mse, doppler, noise;
} mm_cst;

typedef struct {
    mm_kind kind;
    union {
        mm_cfg cfg;   /* CCCFG, CCCFQ, CACFG */
        mm_cyc cyc;   /* CCCYC, CACYC */
        mm_drq drq;   /* CADRQ */
        mm_data data; /* CCTXD, CATXD, CARXD */
        mm_ack ack;   /* CAACK */
        mm_err err;   /* CAERR */
        mm_rev rev;   /* CAREV */
        mm_xst xst;   /* CAXST */
        mm_cst cst;   /* CACST */
        struct { int src, dest; } ping; /* CCMPC */
    } u;
} mm_msg;

/* Parses one sentence of the subset into *m. Returns 0, or -1 with *why (a
 * static string, counted by the driver) for a malformed one: "bad address",
 * "odd hex length", "bad hex", "data longer than any frame", "unknown rate",
 * "missing fields", ... A CC or CA sentence outside the subset, or another
 * talker, returns 1 with m->kind = MM_NONE and *why = "not in the subset". */
int mm_parse(const nmea_sentence *s, mm_msg *m, const char **why);

/* The sentence body of *m ("CCCYC,0,1,2,0,0,1") into out (size n). Returns its
 * length, or -1 if m is out of range (the same checks as mm_parse) or the body
 * does not fit. */
int mm_format(const mm_msg *m, char *out, size_t n);

/* Hex digits (even count, either case) into bytes; returns the count, or -1
 * (odd length, a non-hex digit, more than max bytes). */
int mm_hex_decode(const char *hex, uint8_t *out, int max);

#endif
