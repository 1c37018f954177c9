/* auv-driver-replay: a recorded day at sea decoded again. Reads the
 * <VEHICLE>.RAW.<DEVICE> messages (raw_bytes_t) of an LCM log and feeds the
 * bytes read from the device, with their recorded receive times, through the
 * driver's own protocol code, then publishes the decoded messages on LCM or
 * prints them. A gap in the recorded offsets (a message lost from the log)
 * resets the parser, as a lost port does, and is counted. Every protocol
 * linked in is available (DRV_REGISTER): --device GPS, DVL, ...
 *
 *   auv-driver-replay LOG --vehicle ID --device NAME [--print | --lcm-url URL] [driver flags] */
#include <lcm/eventlog.h>
#include <lcm/lcm.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_raw_bytes_t.h"
#include "common/lcm_rx.h"
#include "common/msg_print.h"
#include "drivers/common/drv_protocol.h"

static void usage(FILE *out)
{
    fprintf(out,
            "usage: auv-driver-replay LOG --vehicle ID --device NAME [--print | --lcm-url URL] [driver flags]\n\n"
            "Decodes the raw bytes a driver recorded (--raw: <ID>.RAW.<NAME>, raw_bytes_t) in an LCM log\n"
            "again, through the same protocol code, and publishes the messages on LCM (--lcm-url) or prints\n"
            "them on stdout, one line each (--print). The driver's own flags (e.g. --origin for GPS) apply.\n"
            "A summary of frames and drops per reason goes to stderr. Devices:");
    for (int i = 0; i < drv_count(); i++)
        fprintf(out, " %s", drv_at(i)->device);
    fprintf(out, "\n\n  LOG             an LCM log with <ID>.RAW.<NAME>\n"
                 "  --vehicle ID    the vehicle whose bytes to decode\n"
                 "  --device NAME   the device (its driver's protocol)\n"
                 "  --print         print the decoded messages on stdout\n"
                 "  --lcm-url URL   publish them on LCM instead\n");
    for (int i = 0; i < drv_count(); i++)
        for (const drv_flag *f = drv_at(i)->flags; f && f->name; f++) {
            char head[64];
            snprintf(head, sizeof head, "%s%s%s", f->name, f->arg ? " " : "", f->arg ? f->arg : "");
            fprintf(out, "  %-15s (%s) %s\n", head, drv_at(i)->device, f->help);
        }
    fprintf(out, "\nSee docs/drivers.md.\n");
}

typedef struct {
    lcm_t *lcm; /* NULL: print */
} sink_target;

static void sink(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    sink_target *t = user;
    if (t->lcm) {
        lcm_publish(t->lcm, channel, data, (unsigned)len);
        return;
    }
    void *msg = calloc(1, type->struct_size);
    if (msg && rx_decode(type, data, len, msg) == 0) {
        printf("%s ", channel);
        msg_print(stdout, type, msg);
        type->info()->decode_cleanup(msg);
    }
    free(msg);
}

int main(int argc, char **argv)
{
    const char *log_path = NULL, *vehicle = NULL, *device = NULL, *url = NULL;
    int print = 0;
    /* the device first: its flags are known only then */
    for (int i = 1; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--device"))
            device = argv[i + 1];
    const drv_protocol *p = device ? drv_find(device) : NULL;
    void *state = p ? calloc(1, p->state_size ? p->state_size : 1) : NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            free(state);
            return 0;
        }
        if (!strcmp(a, "--print")) {
            print = 1;
            continue;
        }
        const drv_flag *own = NULL;
        for (const drv_flag *f = p ? p->flags : NULL; f && f->name; f++)
            if (!strcmp(a, f->name))
                own = f;
        if (a[0] != '-') {
            if (log_path) {
                fprintf(stderr, "auv-driver-replay: one log only ('%s', '%s')\n", log_path, a);
                return 2;
            }
            log_path = a;
            continue;
        }
        const char *v = NULL;
        if (!own || own->arg) {
            if (i + 1 >= argc) {
                fprintf(stderr, "auv-driver-replay: %s needs a value\n", a);
                return 2;
            }
            v = argv[++i];
        }
        char err[256] = "";
        if (own) {
            if (own->set(state, v, err, sizeof err) < 0) {
                fprintf(stderr, "auv-driver-replay: %s\n", err);
                return 2;
            }
        } else if (!strcmp(a, "--vehicle")) {
            vehicle = v;
        } else if (!strcmp(a, "--device")) {
            /* taken above */
        } else if (!strcmp(a, "--lcm-url") || !strcmp(a, "--url")) {
            url = v;
        } else {
            fprintf(stderr, "auv-driver-replay: unknown option %s (see --help)\n", a);
            return 2;
        }
    }
    if (!log_path || !vehicle || !device || (print && url)) {
        fprintf(stderr, "auv-driver-replay: give LOG, --vehicle and --device, and at most one of --print and "
                        "--lcm-url (see --help)\n");
        free(state);
        return 2;
    }
    if (!p) {
        fprintf(stderr, "auv-driver-replay: no driver for device '%s' (see --help)\n", device);
        free(state);
        return 2;
    }
    lcm_eventlog_t *log = lcm_eventlog_create(log_path, "r");
    if (!log) {
        fprintf(stderr, "auv-driver-replay: cannot read %s\n", log_path);
        free(state);
        return 1;
    }
    sink_target target = {NULL};
    if (!print && !(target.lcm = lcm_create(url))) {
        fprintf(stderr, "auv-driver-replay: cannot open LCM at %s\n", url ? url : "(default)");
        lcm_eventlog_destroy(log);
        free(state);
        return 1;
    }
    drv_ctx ctx;
    drv_ctx_init(&ctx, "auv-driver-replay", vehicle, p->device, sink, &target);
    int rc = 0;
    if (p->init && p->init(state, &ctx) < 0) {
        rc = 1;
        goto out;
    }
    char channel[160];
    snprintf(channel, sizeof channel, "%s.RAW.%s", vehicle, p->device);
    const auv_type_entry_t *raw_type = auv_type_find("raw_bytes_t");
    int64_t expect_offset = -1, last = 0, bytes = 0, chunks = 0;
    lcm_eventlog_event_t *ev;
    while ((ev = lcm_eventlog_read_next_event(log))) {
        auv_raw_bytes_t m;
        if (strcmp(ev->channel, channel) != 0) {
            lcm_eventlog_free_event(ev);
            continue;
        }
        if (rx_decode(raw_type, ev->data, (int)ev->datalen, &m) != 0) {
            drv_drop(&ctx, "undecodable raw message", "event %lld", (long long)ev->eventnum);
            lcm_eventlog_free_event(ev);
            continue;
        }
        if (m.direction == AUV_RAW_BYTES_T_DIR_RX && m.n_bytes > 0) {
            if (expect_offset >= 0 && m.offset != expect_offset) {
                drv_drop(&ctx, "gap in the log", "%lld bytes missing before offset %lld",
                         (long long)(m.offset - expect_offset), (long long)m.offset);
                if (p->reset)
                    p->reset(state, &ctx);
            }
            expect_offset = m.offset + m.n_bytes;
            if (p->tick)
                p->tick(state, &ctx, m.utime);
            p->feed(state, &ctx, m.data, (size_t)m.n_bytes, m.utime);
            last = m.utime;
            bytes += m.n_bytes;
            chunks++;
        }
        auv_raw_bytes_t_decode_cleanup(&m);
        lcm_eventlog_free_event(ev);
    }
    if (p->finish)
        p->finish(state, &ctx, last);
    fprintf(stderr, "auv-driver-replay: %s: %lld bytes in %lld reads, %lld frames, %lld messages, %lld dropped",
            channel, (long long)bytes, (long long)chunks, (long long)ctx.frames_decoded,
            (long long)ctx.messages_published, (long long)ctx.reasons.total);
    for (int i = 0; i < ctx.reasons.n; i++)
        fprintf(stderr, "%s %s: %lld", i ? "," : ":", ctx.reasons.name[i], (long long)ctx.reasons.count[i]);
    fprintf(stderr, "\n");
out:
    if (target.lcm)
        lcm_destroy(target.lcm);
    lcm_eventlog_destroy(log);
    free(state);
    return rc;
}
