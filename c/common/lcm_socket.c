#include "common/lcm_socket.h"

#include <dirent.h>
#include <netinet/in.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>

#define DEFAULT_PORT 7667

int lcm_url_port(const char *url)
{
    if (!url || !*url)
        url = getenv("LCM_DEFAULT_URL");
    if (!url || !*url)
        return DEFAULT_PORT;
    if (strncmp(url, "udpm://", 7) != 0)
        return -1;
    const char *host = url + 7, *end = host + strcspn(host, "?");
    const char *colon = memchr(host, ':', (size_t)(end - host));
    if (!colon)
        return DEFAULT_PORT;
    long port = strtol(colon + 1, NULL, 10);
    return port > 0 && port < 65536 ? (int)port : -1;
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
