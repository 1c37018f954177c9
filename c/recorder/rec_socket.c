#include "recorder/rec_socket.h"

#include "common/lcm_socket.h"

#include <stdio.h>
#include <sys/socket.h>

/* The first socket on the port: the recorder has one LCM instance. */
static int take_first(int fd, ino_t inode, void *user)
{
    rec_socket *s = user;
    s->fd = fd;
    s->inode = (unsigned long)inode;
    socklen_t len = sizeof s->granted_bytes;
    getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &s->granted_bytes, &len);
    return 1;
}

int rec_socket_find(rec_socket *s, int port)
{
    s->fd = -1;
    s->inode = 0;
    s->granted_bytes = 0;
    if (port <= 0 || lcm_sockets_on_port(port, take_first, s) < 0)
        return -1;
    return s->fd >= 0 ? 0 : -1;
}

int64_t rec_socket_drops(const rec_socket *s)
{
    if (s->fd < 0)
        return -1;
    FILE *f = fopen("/proc/self/net/udp", "r");
    if (!f)
        return -1;
    char line[512];
    int64_t drops = -1;
    if (!fgets(line, sizeof line, f)) {   /* the header */
        fclose(f);
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        /* sl local rem st tx:rx tr:when retrnsmt uid timeout inode ref pointer drops */
        unsigned long inode = 0;
        long long d = 0;
        if (sscanf(line, " %*s %*s %*s %*s %*s %*s %*s %*s %*s %lu %*s %*s %lld", &inode, &d) == 2 &&
            inode == s->inode) {
            drops = d;
            break;
        }
    }
    fclose(f);
    return drops;
}

long rec_rmem_max(void)
{
    FILE *f = fopen("/proc/sys/net/core/rmem_max", "r");
    long v = -1;
    if (f) {
        if (fscanf(f, "%ld", &v) != 1)
            v = -1;
        fclose(f);
    }
    return v;
}
