/* A kernel-side channel filter on an LCM udpm receive socket.
 *
 * Why: on one udpm group the kernel hands every datagram of the world to every
 * socket joined to it, and liblcm drops the channels nobody subscribed to only
 * after its receive thread has woken, copied and matched them. With N vehicles
 * every process pays for the traffic of all N: O(N^2) receive work for the
 * world (docs/performance.md). A classic BPF program on the socket
 * (SO_ATTACH_FILTER) drops those datagrams in the kernel before they are
 * queued, so a process wakes only for the channels it subscribed to. The group
 * stays one group: lcm-spy, lcm-logger and auv-recorder still hear everything.
 *
 * What it drops: an unfragmented LCM datagram (magic LC02) whose channel
 * matches none of the patterns. Fragments (LC03), anything that is not LCM,
 * and everything while one pattern is more than a name with `.` wildcards and
 * an optional trailing `.*` (what lcm_subscribe's anchored regex means for
 * such a pattern, byte for byte) are let through: liblcm decides, as without
 * the filter. AUV_LCM_CHANFILTER=0 in the environment turns it off.
 *
 * Which socket: liblcm does not expose its receive socket (lcm_get_fileno is
 * a notification pipe), so auv_chanfilter_new() notes the process's sockets on
 * the URL's port before the instance makes its own (at its first subscribe or
 * lcm_get_fileno), and the filter takes the one new socket it finds after a
 * subscribe. Two new ones (another instance made its socket in between): it
 * cannot tell which is its own, and filters nothing. */
#ifndef AUV_LCM_CHANFILTER_H
#define AUV_LCM_CHANFILTER_H

typedef struct auv_chanfilter auv_chanfilter_t;

/* What a socket lets through: a channel pattern, and optionally bytes the
 * message must carry at an offset of its encoding (0: the fingerprint). A
 * process that wants one participant's reports of a shared channel wakes for
 * those only. The payload condition needs a pattern of known length (no
 * trailing `.*`); otherwise it is ignored. */
typedef struct {
    const char *channel;
    const void *payload;
    int payload_at, payload_len;
} auv_chanfilter_rule_t;

/* 0 when AUV_LCM_CHANFILTER=0 in the environment turns every filter off. */
int auv_chanfilter_enabled(void);

/* Right after lcm_create(url) (url NULL: LCM_DEFAULT_URL, else liblcm's
 * default). NULL when there is nothing to filter (not udpm, turned off). */
auv_chanfilter_t *auv_chanfilter_new(const char *url);
void auv_chanfilter_free(auv_chanfilter_t *f);

/* Before lcm_subscribe(pattern): adds the pattern and, if the socket is known,
 * attaches the widened program at once (no window in which a subscribed
 * channel is dropped). Returns 0, -1 out of memory. */
int auv_chanfilter_note(auv_chanfilter_t *f, const char *pattern);
/* The same for a rule with a payload condition (the bytes are copied). */
int auv_chanfilter_note_rule(auv_chanfilter_t *f, const auv_chanfilter_rule_t *rule);

/* After lcm_subscribe: finds the instance's socket if not yet known, and
 * attaches the program. Returns 1 when the socket filters, 0 when it does not
 * (not found yet, ambiguous, a pattern it cannot express), -1 when the kernel
 * refused the program (errno set; the socket then filters nothing). */
int auv_chanfilter_apply(auv_chanfilter_t *f);

/* Attaches the program for rules to a socket of one's own (a process that
 * reads the group itself: common/lcm_udpm_reader.h). Same returns as
 * auv_chanfilter_apply; AUV_LCM_CHANFILTER=0 is the caller's to honour. */
int auv_chanfilter_attach_fd(int fd, const auv_chanfilter_rule_t *rules, int n);

/* Builds the program for rules (no socket involved): writes at most cap
 * instructions of struct sock_filter to out. Returns the count, 0 when a
 * rule cannot be expressed (accept everything), -1 when cap is too small.
 * For tests and the fuzzer. */
int auv_chanfilter_compile(const auv_chanfilter_rule_t *rules, int n, void *out, int cap);

/* The registry of C programs: one filter per lcm_t, found by rx_subscribe. */
void auv_chanfilter_register(const void *lcm, auv_chanfilter_t *f);
auv_chanfilter_t *auv_chanfilter_of(const void *lcm);
void auv_chanfilter_unregister(const void *lcm);

#endif
