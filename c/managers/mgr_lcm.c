/* Open LCM with a receive buffer large enough for the largest command the
 * manager accepts (a LOAD_PLAN of MGR_MAX_PLAN_BYTES), and find out what the
 * kernel actually grants: net.core.rmem_max may cap it, and a fragmented
 * message that does not fit the buffer is lost without a trace. When the
 * buffer cannot be had, the manager accepts smaller plans and says so. The
 * sizes, and why they are what they are: mgr_limits.h. */
#include "managers/mgr_lcm.h"

#include "common/lcm_rx.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#define DEFAULT_URL "udpm://239.255.76.67:7667?ttl=0"

static size_t granted_rcvbuf(size_t want)
{
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    if (fd < 0)
        return 0;
    int v = want > (size_t)(1 << 30) ? 1 << 30 : (int)want, got = 0;
    socklen_t len = sizeof got;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &v, sizeof v);
    getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &got, &len);
    close(fd);
    return got > 0 ? (size_t)got : 0; /* the kernel doubles what it grants: this is the capacity */
}

lcm_t *mgr_lcm_open(const char *url_opt, const char *who, size_t *max_plan_bytes)
{
    const char *base = url_opt ? url_opt : getenv("LCM_DEFAULT_URL");
    if (!base || !*base)
        base = DEFAULT_URL;
    const size_t need = (size_t)MGR_MAX_PLAN_BYTES + 2 * MGR_LCM_FRAGMENT_BYTES; /* capacity for the maximum */
    const size_t want = MGR_RECV_BUFFER_BYTES / 2;                              /* what to ask: the kernel doubles */
    char url[1024];
    int is_udpm = !strncmp(base, "udpm://", 7);
    if (is_udpm && !strstr(base, "recv_buf_size="))
        snprintf(url, sizeof url, "%s%crecv_buf_size=%zu", base, strchr(base, '?') ? '&' : '?', want);
    else
        snprintf(url, sizeof url, "%s", base);
    lcm_t *lcm = rx_lcm_create(url); /* filtered: wakes for its own channels only */
    if (!lcm) {
        fprintf(stderr, "%s: cannot open LCM at %s (no multicast route? see README)\n", who, url);
        return NULL;
    }
    *max_plan_bytes = MGR_MAX_PLAN_BYTES;
    const char *rb = strstr(url, "recv_buf_size=");
    size_t asked = rb ? strtoul(rb + 14, NULL, 10) : 0;
    size_t cap = is_udpm ? granted_rcvbuf(asked ? asked : want) : need;
    if (is_udpm && cap < need) {
        size_t fit = cap > 2 * MGR_LCM_FRAGMENT_BYTES ? cap - 2 * MGR_LCM_FRAGMENT_BYTES : 0;
        if (fit < MGR_MIN_PLAN_BYTES)
            fit = MGR_MIN_PLAN_BYTES;
        if (fit < *max_plan_bytes)
            *max_plan_bytes = fit;
        fprintf(stderr,
                "%s: the kernel grants a %zu-byte receive buffer (net.core.rmem_max caps it; %zu wanted): "
                "LOAD_PLAN accepts plans up to %zu bytes instead of %d (raise it with "
                "`sysctl -w net.core.rmem_max=%zu`)\n",
                who, cap, need, *max_plan_bytes, MGR_MAX_PLAN_BYTES, want);
    }
    return lcm;
}
