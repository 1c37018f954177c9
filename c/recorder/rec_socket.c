#include "recorder/rec_socket.h"

#include <stdio.h>
#include <sys/socket.h>
#include <sys/stat.h>

int rec_socket_of(rec_socket *s, int fd)
{
    s->fd = -1;
    s->inode = 0;
    s->granted_bytes = 0;
    struct stat st;
    if (fd < 0 || fstat(fd, &st) < 0)
        return -1;
    s->fd = fd;
    s->inode = (unsigned long)st.st_ino;
    socklen_t len = sizeof s->granted_bytes;
    getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &s->granted_bytes, &len);
    return 0;
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
