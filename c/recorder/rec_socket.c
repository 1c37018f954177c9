#include "recorder/rec_socket.h"

#include <dirent.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>

int rec_url_port(const char *url)
{
    if (strncmp(url, "udpm://", 7) != 0)
        return -1;
    const char *p = url + 7;
    const char *end = p + strcspn(p, "?");
    const char *colon = memchr(p, ':', (size_t)(end - p));
    if (!colon)
        return 7667;
    return atoi(colon + 1);
}

int rec_socket_find(rec_socket *s, int port)
{
    s->fd = -1;
    s->inode = 0;
    s->granted_bytes = 0;
    if (port <= 0)
        return -1;
    DIR *d = opendir("/proc/self/fd");
    if (!d)
        return -1;
    struct dirent *de;
    while ((de = readdir(d)) != NULL) {
        char *end;
        long fd = strtol(de->d_name, &end, 10);
        if (*end || fd < 0 || fd == dirfd(d))
            continue;
        struct stat st;
        if (fstat((int)fd, &st) || !S_ISSOCK(st.st_mode))
            continue;
        int type = 0;
        socklen_t len = sizeof type;
        if (getsockopt((int)fd, SOL_SOCKET, SO_TYPE, &type, &len) || type != SOCK_DGRAM)
            continue;
        struct sockaddr_in a;
        len = sizeof a;
        if (getsockname((int)fd, (struct sockaddr *)&a, &len) || a.sin_family != AF_INET ||
            ntohs(a.sin_port) != port)
            continue;
        s->fd = (int)fd;
        s->inode = (unsigned long)st.st_ino;
        len = sizeof s->granted_bytes;
        getsockopt((int)fd, SOL_SOCKET, SO_RCVBUF, &s->granted_bytes, &len);
        break;
    }
    closedir(d);
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
