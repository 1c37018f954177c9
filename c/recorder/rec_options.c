#include "recorder/rec_options.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: auv-recorder -f FILE [--lcm-url URL] [--channel REGEX] [--recv-buf BYTES]\n"
            "       [--queue-mb MB] [--lcm-queue N] [--flush-ms MS] [--health-period S]\n"
            "       [--stats FILE.json] [--name NAME] [--no-lockstep] [--quiet]\n"
            "Records every LCM message (or those matching REGEX) to an LCM event log that\n"
            "lcm-logplayer replays. SIGINT/SIGTERM: write out everything received, then exit.\n"
            "--url is the old spelling of --lcm-url.\n");
}

static int number(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    errno = 0;
    double d = strtod(v, &end);
    if (errno || *end || end == v || !(d >= lo && d <= hi)) {
        fprintf(stderr, "auv-recorder: %s: '%s' is not a number in [%g, %g]\n", opt, v, lo, hi);
        return -1;
    }
    *out = d;
    return 0;
}

int rec_parse_args(rec_options *o, int argc, char **argv)
{
    memset(o, 0, sizeof *o);
    o->url = getenv("LCM_DEFAULT_URL") ? getenv("LCM_DEFAULT_URL") : "udpm://239.255.76.67:7667?ttl=0";
    o->channel = ".*";
    o->name = "RECORDER";
    o->recv_buf = 4L << 20;
    o->queue_bytes = (size_t)512 << 20;
    o->lcm_queue = 1000000;
    o->flush_ms = 100;
    o->health_period_s = 1.0;
    o->lockstep = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        double d;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 1;
        }
        if (!strcmp(a, "--no-lockstep")) { o->lockstep = 0; continue; }
        if (!strcmp(a, "--quiet")) { o->quiet = 1; continue; }
        if (!v) {
            fprintf(stderr, "auv-recorder: %s: unknown option or missing value\n", a);
            usage(stderr);
            return 2;
        }
        i++;
        if (!strcmp(a, "-f") || !strcmp(a, "--file")) o->file = v;
        else if (!strcmp(a, "--lcm-url") || !strcmp(a, "--url")) o->url = v;
        else if (!strcmp(a, "--channel")) o->channel = v;
        else if (!strcmp(a, "--stats")) o->stats = v;
        else if (!strcmp(a, "--name")) o->name = v;
        else if (!strcmp(a, "--recv-buf")) {
            if (number(a, v, 0, 1 << 30, &d)) return 2;
            o->recv_buf = (long)d;
        } else if (!strcmp(a, "--queue-mb")) {
            if (number(a, v, 1, 1 << 20, &d)) return 2;
            o->queue_bytes = (size_t)(d * (1 << 20));
        } else if (!strcmp(a, "--lcm-queue")) {
            if (number(a, v, 1, 1 << 30, &d)) return 2;
            o->lcm_queue = (int)d;
        } else if (!strcmp(a, "--flush-ms")) {
            if (number(a, v, 1, 60000, &d)) return 2;
            o->flush_ms = (int)d;
        } else if (!strcmp(a, "--health-period")) {
            if (number(a, v, 0, 3600, &d)) return 2;
            o->health_period_s = d;
        } else {
            fprintf(stderr, "auv-recorder: %s: unknown option\n", a);
            usage(stderr);
            return 2;
        }
    }
    if (!o->file) {
        fprintf(stderr, "auv-recorder: -f FILE is required\n");
        usage(stderr);
        return 2;
    }
    if (strlen(o->name) > 40) {
        fprintf(stderr, "auv-recorder: --name: at most 40 characters\n");
        return 2;
    }
    return 0;
}

char *rec_url_with_recv_buf(const char *url, long bytes)
{
    size_t n = strlen(url) + 48;
    char *s = malloc(n);
    if (!s)
        return NULL;
    if (strncmp(url, "udpm://", 7) != 0 || strstr(url, "recv_buf_size=") || bytes <= 0)
        snprintf(s, n, "%s", url);
    else
        snprintf(s, n, "%s%crecv_buf_size=%ld", url, strchr(url, '?') ? '&' : '?', bytes);
    return s;
}
