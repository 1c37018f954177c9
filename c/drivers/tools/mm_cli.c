/* mm_cli: the Micro-Modem bridge on stdin/stdout, for tests that put the C side
 * and the simulator's emulator (python/sim/devices/micromodem.py) face to face:
 * both sides of the wire must agree on every sentence.
 *
 *   mm_cli --vehicle AUV1 --table AUV1=1,AUV2=2 [--rate R] [--ack] [--no-cst]
 *
 * One command a line; each answer ends with a line ".":
 *   start T                    the configuration sentences
 *   send T SEQ DST|- KIND HEX  a modem_tx_t ("-" broadcasts)
 *   modem T $...*hh            a line from the modem (through the framer)
 *   tick T                     time passing
 *   parse $...*hh              the parsed message alone
 * Answers: "write $...*hh" (a line for the modem), "rx SRC DST|- KIND RATE SNR HEX",
 * "refused TEXT", "bad REASON", "msg KIND", "status k=v ...". */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/modem/mm_bridge.h"

static void print_out(const mm_out *o, const mm_bridge *b)
{
    for (int i = 0; i < o->n_sentences; i++) {
        char line[NMEA_MAX_SENTENCE + 8];
        if (nmea_format(line, sizeof line, o->sentence[i]) > 0)
            printf("write %.*s\n", (int)strcspn(line, "\r\n"), line);
    }
    for (int i = 0; i < o->n_frames; i++) {
        const mm_rx_frame *f = &o->frame[i];
        printf("rx %s %s %d %d %.1f ", f->src_vehicle, f->dst_vehicle[0] ? f->dst_vehicle : "-", f->kind, f->rate,
               f->snr_db);
        for (int k = 0; k < f->n_bytes; k++)
            printf("%02X", f->payload[k]);
        printf("\n");
    }
    const mm_status *s = &b->status;
    if (o->status_changed)
        printf("status sent=%lld received=%lld acked=%lld timeouts=%lld ack_timeouts=%lld modem_errors=%lld "
               "rx_dropped=%lld refused=%lld lost=%lld\n",
               (long long)s->sent, (long long)s->received, (long long)s->acked, (long long)s->timeouts,
               (long long)s->ack_timeouts, (long long)s->modem_errors, (long long)s->rx_dropped,
               (long long)(s->refused_size + s->refused_rate + s->refused_invalid), (long long)s->lost);
}

static int parse_line(const char *text, mm_msg *m, const char **why)
{
    nmea_sentence s;
    nmea_result r = nmea_parse_line(text, strlen(text), 0, &s);
    if (r != NMEA_OK) {
        *why = nmea_result_name(r);
        return -1;
    }
    return mm_parse(&s, m, why);
}

int main(int argc, char **argv)
{
    mm_options o;
    mm_options_default(&o);
    const char *table = "";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--vehicle") && i + 1 < argc)
            o.vehicle = argv[++i];
        else if (!strcmp(argv[i], "--table") && i + 1 < argc)
            table = argv[++i];
        else if (!strcmp(argv[i], "--rate") && i + 1 < argc)
            o.rate = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--ack"))
            o.ack = 1;
        else if (!strcmp(argv[i], "--no-cst"))
            o.cst = 0;
        else {
            fprintf(stderr, "usage: mm_cli --vehicle ID --table ID=ADDR,... [--rate R] [--ack] [--no-cst]\n");
            return 2;
        }
    }
    mm_table t;
    mm_bridge b;
    const char *why;
    if (mm_table_parse(&t, table, &why) || mm_bridge_init(&b, &o, &t, &why)) {
        fprintf(stderr, "mm_cli: %s\n", why);
        return 2;
    }
    static char line[4096];
    static mm_out out;
    while (fgets(line, sizeof line, stdin)) {
        line[strcspn(line, "\r\n")] = 0;
        mm_out_clear(&out);
        char cmd[16] = "", arg[4096] = "";
        long long now = 0;
        if (sscanf(line, "%15s", cmd) != 1)
            continue;
        if (!strcmp(cmd, "parse")) {
            mm_msg m;
            int rc = parse_line(line + 6, &m, &why);
            if (rc)
                printf("bad %s\n", why);
            else
                printf("msg %s\n", mm_kind_name(m.kind));
        } else if (sscanf(line, "%15s %lld %4095[^\n]", cmd, &now, arg) >= 2) {
            if (!strcmp(cmd, "start")) {
                mm_bridge_start(&b, now, &out);
            } else if (!strcmp(cmd, "tick")) {
                mm_bridge_tick(&b, now, &out);
            } else if (!strcmp(cmd, "modem")) {
                mm_msg m;
                int rc = parse_line(arg, &m, &why);
                if (rc)
                    printf("bad %s\n", why);
                else
                    mm_bridge_input(&b, &m, now, &out);
                mm_bridge_tick(&b, now, &out);
            } else if (!strcmp(cmd, "send")) {
                int seq, kind;
                char dst[64], hex[600];
                uint8_t payload[MM_MAX_FRAME_BYTES + 1];
                int n = -1;
                if (sscanf(arg, "%d %63s %d %599s", &seq, dst, &kind, hex) == 4)
                    n = mm_hex_decode(hex, payload, (int)sizeof payload);
                if (n < 0)
                    printf("bad send arguments\n");
                else if (mm_bridge_send(&b, seq, strcmp(dst, "-") ? dst : "", kind, payload, n, now, &out))
                    printf("refused %s\n", b.status.last_refusal);
            } else {
                printf("bad command %s\n", cmd);
            }
            print_out(&out, &b);
        } else {
            printf("bad command %s\n", cmd);
        }
        printf(".\n");
        fflush(stdout);
    }
    return 0;
}
