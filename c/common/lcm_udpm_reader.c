#define _GNU_SOURCE /* recvmmsg */
#include "common/lcm_udpm_reader.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include "common/lcm_socket.h"

#define MAGIC_SHORT 0x4c433032u /* "LC02" */
#define MAGIC_FRAG 0x4c433033u  /* "LC03" */
#define SHORT_HEADER 8
#define FRAG_HEADER 20
#define CHANNEL_MAX 63          /* LCM's limit on a channel name */
#define MESSAGE_MAX (1 << 28)   /* liblcm refuses bigger messages too */
#define BATCH 64                /* datagrams per recvmmsg */
#define DATAGRAM_MAX 65536
#define SLOTS 8                 /* messages being reassembled at once */

/* A fragmented message being put together. */
typedef struct {
    struct sockaddr_in from;
    uint32_t seq;
    uint32_t size, got_bytes;
    uint16_t n, got;
    uint8_t *have;              /* one byte per fragment: arrived */
    uint8_t *data;
    char channel[CHANNEL_MAX + 1];
    uint64_t age;               /* for eviction: the oldest goes first */
    int used;
} frag_slot;

struct lcm_udpm_reader {
    int fd;
    int granted;
    int64_t kernel_drops;
    uint64_t clock;             /* slot ages */
    lcm_udpm_counts counts;
    frag_slot slots[SLOTS];
    frag_slot *completed;       /* handed out by the last next(): freed by the one after */
    int batch_n, batch_i;       /* datagrams read, and taken, of the current batch */
    int batch;                  /* datagrams to read at once (at most BATCH) */
    struct mmsghdr msgs[BATCH];
    struct iovec iov[BATCH];
    struct sockaddr_in from[BATCH];
    char ctrl[BATCH][CMSG_SPACE(sizeof(struct timeval)) + CMSG_SPACE(sizeof(uint32_t))];
    uint8_t bufs[BATCH][DATAGRAM_MAX];
};

int lcm_udpm_reader_enabled(void)
{
    const char *v = getenv("AUV_LCM_READER");
    return !(v && !strcmp(v, "0"));
}

int lcm_udpm_pattern_compile(regex_t *re, const char *pattern)
{
    size_t n = strlen(pattern) + 5;
    char *anchored = malloc(n);
    if (!anchored)
        return REG_ESPACE;
    snprintf(anchored, n, "^(%s)$", pattern);
    int rc = regcomp(re, anchored, REG_EXTENDED | REG_NOSUB);
    free(anchored);
    return rc;
}

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static uint16_t be16(const uint8_t *p)
{
    return (uint16_t)(p[0] << 8 | p[1]);
}

static int fail(char *err, size_t errlen, const char *what, int fd)
{
    if (err && errlen)
        snprintf(err, errlen, "%s: %s", what, strerror(errno));
    if (fd >= 0)
        close(fd);
    return -1;
}

static int open_socket(const char *group, int port, long recv_buf, int *granted, char *err, size_t errlen)
{
    struct in_addr g;
    if (inet_pton(AF_INET, group, &g) != 1) {
        errno = EINVAL;
        return fail(err, errlen, "the group is not an IPv4 address", -1);
    }
    int fd = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return fail(err, errlen, "socket", -1);
    int one = 1;
    /* every LCM process on the machine binds the same port */
    if (setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) < 0)
        return fail(err, errlen, "SO_REUSEADDR", fd);
    if (recv_buf > 0) {
        int want = recv_buf > (1L << 30) ? 1 << 30 : (int)recv_buf;
        setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &want, sizeof want); /* capped by rmem_max: read back */
    }
    socklen_t len = sizeof *granted;
    getsockopt(fd, SOL_SOCKET, SO_RCVBUF, granted, &len);
    setsockopt(fd, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof one);
    setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);
    struct sockaddr_in a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_ANY);
    a.sin_port = htons((uint16_t)port);
    if (bind(fd, (struct sockaddr *)&a, sizeof a) < 0)
        return fail(err, errlen, "bind", fd);
    struct ip_mreq mreq;
    mreq.imr_multiaddr = g;
    mreq.imr_interface.s_addr = htonl(INADDR_ANY);
    if (setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &mreq, sizeof mreq) < 0)
        return fail(err, errlen, "joining the multicast group", fd);
    return fd;
}

lcm_udpm_reader_t *lcm_udpm_reader_open(const char *url, long recv_buf, char *err, size_t errlen)
{
    char group[64];
    int port;
    long url_buf;
    if (lcm_udpm_url_parse(url, group, sizeof group, &port, &url_buf) != 0) {
        if (err && errlen)
            snprintf(err, errlen, "not a udpm url: %s", url ? url : "(default)");
        return NULL;
    }
    lcm_udpm_reader_t *r = calloc(1, sizeof *r);
    if (!r) {
        fail(err, errlen, "out of memory", -1);
        return NULL;
    }
    r->batch = BATCH;
    r->fd = open_socket(group, port, url_buf > 0 ? url_buf : recv_buf, &r->granted, err, errlen);
    if (r->fd < 0) {
        free(r);
        return NULL;
    }
    return r;
}

static void slot_free(frag_slot *s)
{
    free(s->have);
    free(s->data);
    memset(s, 0, sizeof *s);
}

void lcm_udpm_reader_close(lcm_udpm_reader_t *r)
{
    if (!r)
        return;
    for (int i = 0; i < SLOTS; i++)
        slot_free(&r->slots[i]);
    close(r->fd);
    free(r);
}

int lcm_udpm_reader_fd(const lcm_udpm_reader_t *r)
{
    return r->fd;
}

int64_t lcm_udpm_reader_kernel_drops(const lcm_udpm_reader_t *r)
{
    return r->kernel_drops;
}

int lcm_udpm_reader_granted(const lcm_udpm_reader_t *r)
{
    return r->granted;
}

const lcm_udpm_counts *lcm_udpm_reader_counts(const lcm_udpm_reader_t *r)
{
    return &r->counts;
}

/* The slot of (from, seq): found, or a new one (evicting the oldest, whose
 * message can no longer complete). NULL when the header is not acceptable. */
static frag_slot *slot_for(lcm_udpm_reader_t *r, const struct sockaddr_in *from, uint32_t seq, uint32_t size,
                           uint16_t n)
{
    frag_slot *free_slot = NULL, *oldest = NULL;
    for (int i = 0; i < SLOTS; i++) {
        frag_slot *s = &r->slots[i];
        if (!s->used) {
            free_slot = free_slot ? free_slot : s;
            continue;
        }
        if (s->from.sin_addr.s_addr == from->sin_addr.s_addr && s->from.sin_port == from->sin_port) {
            if (s->seq == seq && s->size == size && s->n == n)
                return s;
            /* a sender sends one message at a time: its older one is lost */
            r->counts.incomplete++;
            slot_free(s);
            free_slot = free_slot ? free_slot : s;
            continue;
        }
        if (!oldest || s->age < oldest->age)
            oldest = s;
    }
    if (!free_slot) {
        r->counts.incomplete++;
        slot_free(oldest);
        free_slot = oldest;
    }
    free_slot->have = calloc(n, 1);
    free_slot->data = malloc(size ? size : 1);
    if (!free_slot->have || !free_slot->data) {
        slot_free(free_slot);
        return NULL;
    }
    free_slot->used = 1;
    free_slot->from = *from;
    free_slot->seq = seq;
    free_slot->size = size;
    free_slot->n = n;
    free_slot->age = ++r->clock;
    return free_slot;
}

static int64_t stamp_of(const struct msghdr *h, lcm_udpm_reader_t *r)
{
    int64_t t = 0;
    for (struct cmsghdr *c = CMSG_FIRSTHDR(h); c; c = CMSG_NXTHDR((struct msghdr *)h, c)) {
        if (c->cmsg_level != SOL_SOCKET)
            continue;
        if (c->cmsg_type == SO_TIMESTAMP) {
            struct timeval tv;
            memcpy(&tv, CMSG_DATA(c), sizeof tv);
            t = (int64_t)tv.tv_sec * 1000000 + tv.tv_usec;
        } else if (c->cmsg_type == SO_RXQ_OVFL) {
            uint32_t d;
            memcpy(&d, CMSG_DATA(c), sizeof d);
            r->kernel_drops = d;
        }
    }
    if (!t) {
        struct timeval tv;
        gettimeofday(&tv, NULL);
        t = (int64_t)tv.tv_sec * 1000000 + tv.tv_usec;
    }
    return t;
}

/* 1 when the n bytes at p are UTF-8 (no overlong forms, no surrogates). */
static int utf8_ok(const uint8_t *p, int n)
{
    for (int i = 0; i < n;) {
        uint8_t c = p[i];
        int more = c < 0x80 ? 0 : (c & 0xE0) == 0xC0 ? 1 : (c & 0xF0) == 0xE0 ? 2 : (c & 0xF8) == 0xF0 ? 3 : -1;
        if (more < 0 || i + more >= n) /* not a lead byte, or cut short */
            return 0;
        uint32_t cp = more == 0 ? c : more == 1 ? c & 0x1Fu : more == 2 ? c & 0x0Fu : c & 0x07u;
        for (int k = 1; k <= more; k++) {
            if ((p[i + k] & 0xC0) != 0x80)
                return 0;
            cp = cp << 6 | (p[i + k] & 0x3Fu);
        }
        static const uint32_t least[4] = {0, 0x80, 0x800, 0x10000};
        if (cp < least[more] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
            return 0;
        i += more + 1;
    }
    return 1;
}

/* The channel at p (at most `avail` bytes): its length, -1 when it has no
 * terminator within LCM's limit, is empty or is not UTF-8 (every reader of
 * the log - lcm.EventLog, lcm-spy - takes channel names as text). */
static int channel_len(const uint8_t *p, size_t avail)
{
    size_t max = avail < CHANNEL_MAX + 1 ? avail : CHANNEL_MAX + 1;
    const uint8_t *nul = memchr(p, 0, max);
    if (!nul || nul == p || !utf8_ok(p, (int)(nul - p)))
        return -1;
    return (int)(nul - p);
}

/* 1 when the fragment completed a message (in m). */
static int on_fragment(lcm_udpm_reader_t *r, const uint8_t *p, size_t len, const struct sockaddr_in *from,
                       lcm_udpm_msg *m)
{
    if (len < FRAG_HEADER)
        return r->counts.malformed++, 0;
    uint32_t seq = be32(p + 4), size = be32(p + 8), off = be32(p + 12);
    uint16_t no = be16(p + 16), n = be16(p + 18);
    if (n == 0 || no >= n || size > MESSAGE_MAX)
        return r->counts.malformed++, 0;
    const uint8_t *d = p + FRAG_HEADER;
    size_t dlen = len - FRAG_HEADER;
    char channel[CHANNEL_MAX + 1] = "";
    if (no == 0) {
        int cl = channel_len(d, dlen);
        if (cl < 0)
            return r->counts.malformed++, 0;
        memcpy(channel, d, (size_t)cl + 1);
        d += cl + 1;
        dlen -= (size_t)cl + 1;
    }
    if (off > size || dlen > size - off)
        return r->counts.malformed++, 0;
    frag_slot *s = slot_for(r, from, seq, size, n);
    if (!s)
        return 0;
    if (s->have[no])
        return 0; /* a duplicate */
    s->have[no] = 1;
    s->got++;
    s->got_bytes += (uint32_t)dlen;
    memcpy(s->data + off, d, dlen);
    if (no == 0)
        memcpy(s->channel, channel, sizeof channel);
    if (s->got < s->n)
        return 0;
    if (s->got_bytes != s->size) {
        r->counts.malformed++;
        slot_free(s);
        return 0;
    }
    m->channel = s->channel;
    m->data = s->data;
    m->len = (int)s->size;
    r->completed = s;
    return 1;
}

/* 1 when the datagram is (or completed) a message, in m. */
static int on_datagram(lcm_udpm_reader_t *r, uint8_t *p, size_t len, const struct sockaddr_in *from, lcm_udpm_msg *m)
{
    r->counts.datagrams++;
    uint32_t magic = len >= 4 ? be32(p) : 0;
    if (magic == MAGIC_FRAG)
        return on_fragment(r, p, len, from, m);
    if (magic != MAGIC_SHORT || len < SHORT_HEADER + 1)
        return r->counts.malformed++, 0;
    int cl = channel_len(p + SHORT_HEADER, len - SHORT_HEADER);
    if (cl < 0)
        return r->counts.malformed++, 0;
    m->channel = (const char *)p + SHORT_HEADER;
    m->data = p + SHORT_HEADER + cl + 1;
    m->len = (int)(len - SHORT_HEADER - (size_t)cl - 1);
    return 1;
}

/* Reads the next batch; 0 when nothing is queued, -1 on an error. */
static int refill(lcm_udpm_reader_t *r)
{
    for (int i = 0; i < BATCH; i++) {
        r->iov[i].iov_base = r->bufs[i];
        r->iov[i].iov_len = DATAGRAM_MAX;
        struct msghdr *h = &r->msgs[i].msg_hdr;
        memset(h, 0, sizeof *h);
        h->msg_iov = &r->iov[i];
        h->msg_iovlen = 1;
        h->msg_name = &r->from[i];
        h->msg_namelen = sizeof r->from[i];
        h->msg_control = r->ctrl[i];
        h->msg_controllen = sizeof r->ctrl[i];
    }
    int got;
    do
        got = recvmmsg(r->fd, r->msgs, (unsigned)r->batch, MSG_DONTWAIT, NULL);
    while (got < 0 && errno == EINTR);
    if (got < 0)
        return errno == EAGAIN || errno == EWOULDBLOCK ? 0 : -1;
    r->batch_n = got;
    r->batch_i = 0;
    return got;
}

int lcm_udpm_reader_next(lcm_udpm_reader_t *r, lcm_udpm_msg *m)
{
    if (r->completed) {
        slot_free(r->completed);
        r->completed = NULL;
    }
    for (;;) {
        if (r->batch_i == r->batch_n) {
            int rc = refill(r);
            if (rc <= 0)
                return rc;
        }
        int i = r->batch_i++;
        struct msghdr *h = &r->msgs[i].msg_hdr;
        if (h->msg_flags & MSG_TRUNC) { /* cannot be LCM: a datagram is at most 64 KB */
            r->counts.datagrams++;
            r->counts.malformed++;
            continue;
        }
        m->recv_utime = stamp_of(h, r);
        if (on_datagram(r, r->bufs[i], r->msgs[i].msg_len, &r->from[i], m)) {
            r->counts.messages++;
            return 1;
        }
    }
}

void lcm_udpm_reader_set_batch(lcm_udpm_reader_t *r, int n)
{
    r->batch = n < 1 ? 1 : n > BATCH ? BATCH : n;
}

int lcm_udpm_reader_pending(const lcm_udpm_reader_t *r)
{
    return r->batch_i < r->batch_n;
}

int lcm_udpm_reader_drain(lcm_udpm_reader_t *r, lcm_udpm_handler fn, void *user)
{
    int delivered = 0;
    lcm_udpm_msg m;
    int rc;
    while ((rc = lcm_udpm_reader_next(r, &m)) == 1) {
        fn(m.channel, m.data, m.len, m.recv_utime, user);
        delivered++;
    }
    return rc < 0 && !delivered ? -1 : delivered;
}
