/* Finding an LCM instance's receive socket and keeping its channel filter
 * (lcm_chanfilter.h) in step with its subscriptions. */
#include "common/lcm_chanfilter.h"

#include "common/lcm_socket.h"

#include <errno.h>
#include <linux/filter.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>

#define MAX_BEFORE 64
#define MAX_PROGRAM BPF_MAXINSNS

enum { SEARCHING, FOUND, GAVE_UP };

/* Sockets some filter of this process has taken: another instance's socket
 * made after this one's snapshot is not a candidate for this one. */
#define MAX_CLAIMED 64
static ino_t claimed[MAX_CLAIMED];
static int n_claimed;
static pthread_mutex_t claimed_mu = PTHREAD_MUTEX_INITIALIZER;

struct auv_chanfilter {
    int port;
    ino_t before[MAX_BEFORE]; /* this process's sockets on the port before the instance's */
    int n_before;
    int state;
    int fd;
    ino_t ino;
    int attached_n, attached_rc; /* the rules the socket's program has, and attach()'s answer */
    auv_chanfilter_rule_t *rules; /* owning copies */
    int n, cap;
};

static int note_before(int fd, ino_t ino, void *user)
{
    (void)fd;
    auv_chanfilter_t *f = user;
    if (f->n_before < MAX_BEFORE)
        f->before[f->n_before++] = ino;
    else
        f->state = GAVE_UP;
    return 0;
}

int auv_chanfilter_enabled(void)
{
    const char *off = getenv("AUV_LCM_CHANFILTER");
    return !(off && !strcmp(off, "0"));
}

auv_chanfilter_t *auv_chanfilter_new(const char *url)
{
    if (!auv_chanfilter_enabled())
        return NULL;
    int port = lcm_url_port(url);
    if (port < 0)
        return NULL;
    auv_chanfilter_t *f = calloc(1, sizeof *f);
    if (!f)
        return NULL;
    f->port = port;
    f->fd = -1;
    f->attached_n = -1;
    if (lcm_sockets_on_port(port, note_before, f) < 0)
        f->state = GAVE_UP; /* no /proc: filter nothing */
    return f;
}

void auv_chanfilter_free(auv_chanfilter_t *f)
{
    if (!f)
        return;
    pthread_mutex_lock(&claimed_mu);
    for (int i = 0; f->state == FOUND && i < n_claimed; i++)
        if (claimed[i] == f->ino) {
            claimed[i] = claimed[--n_claimed];
            break;
        }
    pthread_mutex_unlock(&claimed_mu);
    for (int i = 0; i < f->n; i++) {
        free((void *)f->rules[i].channel);
        free((void *)f->rules[i].payload);
    }
    free(f->rules);
    free(f);
}

typedef struct {
    const auv_chanfilter_t *f;
    int fd, count;
    ino_t ino;
} search_t;

static int note_new(int fd, ino_t ino, void *user)
{
    search_t *s = user;
    for (int i = 0; i < s->f->n_before; i++)
        if (s->f->before[i] == ino)
            return 0;
    for (int i = 0; i < n_claimed; i++)
        if (claimed[i] == ino)
            return 0;
    s->fd = fd;
    s->ino = ino;
    s->count++;
    return 0;
}

int auv_chanfilter_attach_fd(int fd, const auv_chanfilter_rule_t *rules, int n)
{
    struct sock_filter *ins = malloc(MAX_PROGRAM * sizeof *ins);
    if (!ins)
        return -1;
    int len = auv_chanfilter_compile(rules, n, ins, MAX_PROGRAM);
    int rc = 1;
    if (len > 0) {
        struct sock_fprog prog = {(unsigned short)len, ins};
        if (setsockopt(fd, SOL_SOCKET, SO_ATTACH_FILTER, &prog, sizeof prog) < 0)
            rc = -1;
    } else {
        rc = 0; /* a pattern that is not a name, or too many: everything passes */
    }
    free(ins);
    if (rc != 1) {
        int saved = errno;
        /* A refused program leaves the old, narrower one in place: take it
         * off, so that the new subscription is not dropped. */
        setsockopt(fd, SOL_SOCKET, SO_DETACH_FILTER, NULL, 0);
        errno = saved;
    }
    return rc;
}

static int attach(auv_chanfilter_t *f)
{
    struct stat st;
    if (fstat(f->fd, &st) < 0 || st.st_ino != f->ino) {
        f->state = GAVE_UP; /* the instance closed its socket */
        return 0;
    }
    int rc = auv_chanfilter_attach_fd(f->fd, f->rules, f->n);
    f->attached_n = f->n;
    f->attached_rc = rc;
    return rc;
}

static int same_rule(const auv_chanfilter_rule_t *a, const auv_chanfilter_rule_t *b)
{
    return !strcmp(a->channel, b->channel) && a->payload_len == b->payload_len && a->payload_at == b->payload_at &&
           (a->payload_len <= 0 || !memcmp(a->payload, b->payload, (size_t)a->payload_len));
}

int auv_chanfilter_note_rule(auv_chanfilter_t *f, const auv_chanfilter_rule_t *rule)
{
    if (!f)
        return 0;
    auv_chanfilter_rule_t r = *rule;
    if (!r.payload)
        r.payload_len = 0;
    for (int i = 0; i < f->n; i++)
        if (same_rule(&f->rules[i], &r))
            return 0;
    if (f->n == f->cap) {
        int cap = f->cap ? 2 * f->cap : 8;
        auv_chanfilter_rule_t *p = realloc(f->rules, (size_t)cap * sizeof *p);
        if (!p)
            return -1;
        f->rules = p;
        f->cap = cap;
    }
    char *channel = strdup(r.channel);
    void *payload = r.payload_len > 0 ? malloc((size_t)r.payload_len) : NULL;
    if (!channel || (r.payload_len > 0 && !payload)) {
        free(channel);
        free(payload);
        return -1;
    }
    if (payload)
        memcpy(payload, r.payload, (size_t)r.payload_len);
    f->rules[f->n++] = (auv_chanfilter_rule_t){channel, payload, r.payload_at, r.payload_len};
    if (f->state == FOUND && attach(f) < 0)
        return -1;
    return 0;
}

int auv_chanfilter_note(auv_chanfilter_t *f, const char *pattern)
{
    const auv_chanfilter_rule_t r = {pattern, NULL, 0, 0};
    return auv_chanfilter_note_rule(f, &r);
}

int auv_chanfilter_apply(auv_chanfilter_t *f)
{
    if (!f || f->state == GAVE_UP)
        return 0;
    if (f->state == FOUND && f->attached_n == f->n)
        return f->attached_rc; /* note() attached these rules already */
    if (f->state == SEARCHING) {
        search_t s = {f, -1, 0, 0};
        pthread_mutex_lock(&claimed_mu);
        int rc = lcm_sockets_on_port(f->port, note_new, &s);
        if (rc == 0 && s.count == 1 && n_claimed < MAX_CLAIMED)
            claimed[n_claimed++] = s.ino;
        pthread_mutex_unlock(&claimed_mu);
        if (rc < 0 || s.count > 1) {
            f->state = GAVE_UP;
            return 0;
        }
        if (s.count == 0)
            return 0;
        f->fd = s.fd;
        f->ino = s.ino;
        f->state = FOUND;
    }
    return attach(f);
}

/* ------------------------------------------------------------- registry */

#define MAX_REGISTERED 8

static struct {
    const void *lcm;
    auv_chanfilter_t *f;
} registry[MAX_REGISTERED];

void auv_chanfilter_register(const void *lcm, auv_chanfilter_t *f)
{
    for (int i = 0; i < MAX_REGISTERED; i++)
        if (!registry[i].lcm) {
            registry[i].lcm = lcm;
            registry[i].f = f;
            return;
        }
    auv_chanfilter_free(f); /* full: that instance is not filtered */
}

auv_chanfilter_t *auv_chanfilter_of(const void *lcm)
{
    for (int i = 0; lcm && i < MAX_REGISTERED; i++)
        if (registry[i].lcm == lcm)
            return registry[i].f;
    return NULL;
}

void auv_chanfilter_unregister(const void *lcm)
{
    for (int i = 0; lcm && i < MAX_REGISTERED; i++)
        if (registry[i].lcm == lcm) {
            auv_chanfilter_free(registry[i].f);
            registry[i].lcm = NULL;
            registry[i].f = NULL;
        }
}
