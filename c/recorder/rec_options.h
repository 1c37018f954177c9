/* auv-recorder's command line. */
#ifndef REC_OPTIONS_H
#define REC_OPTIONS_H

#include <stddef.h>

typedef struct {
    const char *file;           /* the log to write */
    const char *url;
    const char *channel;        /* regex, as lcm_subscribe takes it */
    const char *stats;          /* JSON counts at exit, or NULL */
    const char *name;           /* lockstep participant and health process name */
    long recv_buf;              /* socket receive buffer to ask for [bytes] */
    size_t queue_bytes;         /* the writer queue's limit */
    int lcm_queue;              /* liblcm subscription queue [messages] */
    int flush_ms;
    double health_period_s;     /* 0: no health messages */
    int lockstep;               /* take part in lockstep worlds */
    int quiet;
} rec_options;

/* 0 ok, 1 --help shown, 2 usage error (printed). */
int rec_parse_args(rec_options *o, int argc, char **argv);
/* The URL with recv_buf_size added when it is udpm and names none; malloc'd. */
char *rec_url_with_recv_buf(const char *url, long bytes);

#endif
