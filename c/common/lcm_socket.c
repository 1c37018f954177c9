#include "common/lcm_socket.h"

#include <dirent.h>
#include <netinet/in.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>

#define DEFAULT_PORT 7667
#define DEFAULT_GROUP "239.255.76.67"

int lcm_udpm_url_parse(const char *url, char *group, size_t group_len, int *port, long *recv_buf)
{
    if (!url || !*url)
        url = getenv("LCM_DEFAULT_URL");
    if (!url || !*url)
        url = "udpm://" DEFAULT_GROUP;
    if (strncmp(url, "udpm://", 7) != 0)
        return -1;
    const char *host = url + 7, *opts = host + strcspn(host, "?");
    const char *colon = memchr(host, ':', (size_t)(opts - host));
    const char *host_end = colon ? colon : opts;
    size_t n = (size_t)(host_end - host);
    if (n == 0) {
        host = DEFAULT_GROUP;
        n = strlen(DEFAULT_GROUP);
    }
    if (group_len <= n)
        return -1;
    memcpy(group, host, n);
    group[n] = '\0';
    *port = DEFAULT_PORT;
    if (colon) {
        char *end;
        long p = strtol(colon + 1, &end, 10);
        if (end != opts || p <= 0 || p >= 65536)
            return -1;
        *port = (int)p;
    }
    *recv_buf = 0;
    /* options: key=value pairs joined by '&' */
    for (const char *o = *opts ? opts + 1 : opts; *o;) {
        size_t len = strcspn(o, "&");
        if (len > 14 && !strncmp(o, "recv_buf_size=", 14))
            *recv_buf = strtol(o + 14, NULL, 10);
        o += len + (o[len] == '&');
    }
    return 0;
}

int lcm_url_port(const char *url)
{
    char group[64];
    int port;
    long rb;
    return lcm_udpm_url_parse(url, group, sizeof group, &port, &rb) == 0 ? port : -1;
}

int lcm_sockets_on_port(int port, int (*fn)(int fd, ino_t inode, void *user), void *user)
{
    DIR *d = opendir("/proc/self/fd");
    if (!d)
        return -1;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        char *end;
        long fd = strtol(e->d_name, &end, 10);
        struct stat st;
        if (*end || fd < 0 || fd == dirfd(d) || fstat((int)fd, &st) < 0 || !S_ISSOCK(st.st_mode))
            continue;
        int type = 0;
        socklen_t tl = sizeof type;
        struct sockaddr_in a;
        socklen_t al = sizeof a;
        if (getsockopt((int)fd, SOL_SOCKET, SO_TYPE, &type, &tl) < 0 || type != SOCK_DGRAM)
            continue;
        if (getsockname((int)fd, (struct sockaddr *)&a, &al) < 0 || a.sin_family != AF_INET ||
            ntohs(a.sin_port) != port)
            continue;
        if (fn((int)fd, st.st_ino, user))
            break;
    }
    closedir(d);
    return 0;
}
