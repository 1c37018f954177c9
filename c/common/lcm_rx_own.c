/* rx instances that read the udpm group on a socket of their own.
 *
 * Why: through liblcm every datagram wakes its receive thread, which then
 * wakes the caller through a pipe - two context switches per message, most
 * of what a manager or auv-nav costs in fast time (docs/performance.md). On
 * its own socket (common/lcm_udpm_reader.h) a process is woken once, by the
 * kernel, and takes what has queued. Messages are still handed over one per
 * rx_handle_timeout call, in arrival order, to the subscriptions in the
 * order they were made, as liblcm does; which subscriptions match a channel
 * is worked out once per channel (anchored POSIX regex) and remembered. The
 * kernel channel filter is rebuilt from the live subscriptions, so it also
 * narrows again when one is dropped. Publishing stays with liblcm. */
#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/lcm_chanfilter.h"
#include "common/lcm_rx_route.h"
#include "common/lcm_udpm_reader.h"

#define CACHE_BUCKETS 256
#define CACHE_MAX 4096          /* channels remembered; past it, matched each time */
#define MAX_INSTANCES 16

typedef struct cache_entry {
    struct cache_entry *next;
    int n;
    struct rx_raw **routes;
    char channel[];
} cache_entry;

struct rx_own {
    lcm_t *lcm;
    lcm_udpm_reader_t *reader;
    int filter_on;
    struct rx_raw *head;
    struct rx_raw *graveyard;   /* removed during a dispatch: freed after it */
    int dispatching;
    cache_entry *cache[CACHE_BUCKETS];
    int cached;
};

static struct {
    const lcm_t *lcm;
    rx_own_t *own;
} registry[MAX_INSTANCES];
static pthread_mutex_t registry_mu = PTHREAD_MUTEX_INITIALIZER;

rx_own_t *rx_own_of(const lcm_t *lcm)
{
    rx_own_t *own = NULL;
    pthread_mutex_lock(&registry_mu);
    for (int i = 0; i < MAX_INSTANCES && !own; i++)
        if (registry[i].lcm == lcm && lcm)
            own = registry[i].own;
    pthread_mutex_unlock(&registry_mu);
    return own;
}

rx_own_t *rx_own_create(lcm_t *lcm, const char *url)
{
    if (!lcm || !lcm_udpm_reader_enabled())
        return NULL;
    char err[160];
    lcm_udpm_reader_t *reader = lcm_udpm_reader_open(url, 0, err, sizeof err);
    if (!reader)
        return NULL; /* not udpm (or the socket failed): liblcm receives, as before */
    rx_own_t *own = calloc(1, sizeof *own);
    if (!own) {
        lcm_udpm_reader_close(reader);
        return NULL;
    }
    own->lcm = lcm;
    own->reader = reader;
    own->filter_on = auv_chanfilter_enabled();
    pthread_mutex_lock(&registry_mu);
    int slot = -1;
    for (int i = 0; i < MAX_INSTANCES && slot < 0; i++)
        if (!registry[i].lcm)
            slot = i;
    if (slot >= 0) {
        registry[slot].lcm = lcm;
        registry[slot].own = own;
    }
    pthread_mutex_unlock(&registry_mu);
    if (slot < 0) {
        lcm_udpm_reader_close(reader);
        free(own);
        return NULL;
    }
    /* No subscription yet: nothing is wanted. */
    if (own->filter_on)
        auv_chanfilter_attach_fd(lcm_udpm_reader_fd(reader), NULL, 0);
    return own;
}

static void cache_clear(rx_own_t *own)
{
    for (int b = 0; b < CACHE_BUCKETS; b++) {
        cache_entry *e = own->cache[b];
        while (e) {
            cache_entry *n = e->next;
            free(e->routes);
            free(e);
            e = n;
        }
        own->cache[b] = NULL;
    }
    own->cached = 0;
}

static void raw_free(struct rx_raw *r)
{
    regfree(&r->re);
    free(r->pattern);
    free(r->payload);
    free(r);
}

static void free_graveyard(rx_own_t *own)
{
    while (own->graveyard) {
        struct rx_raw *n = own->graveyard->next;
        raw_free(own->graveyard);
        own->graveyard = n;
    }
}

void rx_own_destroy(lcm_t *lcm)
{
    rx_own_t *own = rx_own_of(lcm);
    if (!own)
        return;
    pthread_mutex_lock(&registry_mu);
    for (int i = 0; i < MAX_INSTANCES; i++)
        if (registry[i].lcm == lcm)
            registry[i].lcm = NULL, registry[i].own = NULL;
    pthread_mutex_unlock(&registry_mu);
    cache_clear(own);
    free_graveyard(own);
    /* routes still subscribed belong to their rx_sub_t owners: unhook them */
    for (struct rx_raw *r = own->head; r; r = r->next)
        r->own = NULL;
    lcm_udpm_reader_close(own->reader);
    free(own);
}

/* The kernel filter for the live routes. */
static void refilter(rx_own_t *own)
{
    if (!own->filter_on)
        return;
    int n = 0;
    for (struct rx_raw *r = own->head; r; r = r->next)
        n++;
    auv_chanfilter_rule_t *rules = calloc((size_t)n + 1, sizeof *rules);
    if (!rules) { /* out of memory: let everything through rather than lose a subscription */
        static const auv_chanfilter_rule_t everything = {".*", NULL, 0, 0};
        auv_chanfilter_attach_fd(lcm_udpm_reader_fd(own->reader), &everything, 1);
        return;
    }
    int i = 0;
    for (struct rx_raw *r = own->head; r; r = r->next)
        rules[i++] = (auv_chanfilter_rule_t){r->pattern, r->payload, r->payload_at, r->payload_len};
    if (auv_chanfilter_attach_fd(lcm_udpm_reader_fd(own->reader), rules, n) < 0) {
        static int told;
        if (!told++)
            fprintf(stderr, "lcm_rx: the kernel refused the channel filter (%s): this process receives every channel\n",
                    strerror(errno));
    }
    free(rules);
}

int rx_own_add(rx_own_t *own, struct rx_raw *r)
{
    if (lcm_udpm_pattern_compile(&r->re, r->pattern) != 0) {
        fprintf(stderr, "lcm_rx: '%s' is not a channel pattern\n", r->pattern);
        return -1;
    }
    r->own = own;
    struct rx_raw **tail = &own->head;
    while (*tail)
        tail = &(*tail)->next;
    *tail = r;
    r->next = NULL;
    cache_clear(own);
    refilter(own); /* before anything is read for it: nothing of it is dropped */
    return 0;
}

void rx_own_remove(rx_own_t *own, struct rx_raw *r)
{
    for (struct rx_raw **p = &own->head; *p; p = &(*p)->next) {
        if (*p == r) {
            *p = r->next;
            break;
        }
    }
    cache_clear(own);
    refilter(own);
    r->dead = 1;
    if (own->dispatching) {
        r->next = own->graveyard;
        own->graveyard = r;
    } else {
        raw_free(r);
    }
}

static unsigned hash(const char *s)
{
    unsigned h = 2166136261u;
    while (*s)
        h = (h ^ (unsigned char)*s++) * 16777619u;
    return h;
}

/* The routes whose pattern matches channel, in subscription order. */
static cache_entry *routes_for(rx_own_t *own, const char *channel)
{
    unsigned b = hash(channel) % CACHE_BUCKETS;
    for (cache_entry *e = own->cache[b]; e; e = e->next)
        if (!strcmp(e->channel, channel))
            return e;
    int n = 0;
    for (struct rx_raw *r = own->head; r; r = r->next)
        n++;
    size_t len = strlen(channel) + 1;
    cache_entry *e = malloc(sizeof *e + len);
    if (!e)
        return NULL;
    e->routes = malloc(((size_t)n + 1) * sizeof *e->routes);
    if (!e->routes) {
        free(e);
        return NULL;
    }
    memcpy(e->channel, channel, len);
    e->n = 0;
    for (struct rx_raw *r = own->head; r; r = r->next)
        if (regexec(&r->re, channel, 0, NULL, 0) == 0)
            e->routes[e->n++] = r;
    if (own->cached >= CACHE_MAX)
        cache_clear(own); /* a world of endless channel names: start again */
    e->next = own->cache[b];
    own->cache[b] = e;
    own->cached++;
    return e;
}

static void dispatch(rx_own_t *own, const lcm_udpm_msg *m)
{
    cache_entry *e = routes_for(own, m->channel);
    if (!e || e->n == 0)
        return;
    /* A handler may subscribe or unsubscribe (a new plan's inputs): work
     * from a copy; a route dropped meanwhile is only marked dead. */
    struct rx_raw *stack[32], **routes = e->n <= 32 ? stack : malloc((size_t)e->n * sizeof *routes);
    if (!routes)
        return;
    int n = e->n;
    memcpy(routes, e->routes, (size_t)n * sizeof *routes);
    lcm_recv_buf_t rb = {(void *)m->data, (uint32_t)m->len, m->recv_utime, own->lcm};
    own->dispatching++;
    for (int i = 0; i < n; i++)
        if (!routes[i]->dead)
            routes[i]->fn(&rb, m->channel, routes[i]->user);
    own->dispatching--;
    if (routes != stack)
        free(routes);
    if (!own->dispatching)
        free_graveyard(own);
}

int rx_own_handle_timeout(rx_own_t *own, int timeout_ms)
{
    lcm_udpm_msg m;
    int rc = lcm_udpm_reader_next(own->reader, &m);
    if (rc == 0) {
        struct pollfd p = {.fd = lcm_udpm_reader_fd(own->reader), .events = POLLIN};
        int pr = poll(&p, 1, timeout_ms < 0 ? -1 : timeout_ms);
        if (pr < 0)
            return errno == EINTR ? 0 : -1; /* a signal: the caller's loop decides */
        if (pr == 0)
            return 0;
        rc = lcm_udpm_reader_next(own->reader, &m);
    }
    if (rc <= 0)
        return rc;
    dispatch(own, &m);
    return 1;
}
