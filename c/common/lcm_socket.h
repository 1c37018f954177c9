/* Finding an LCM udpm instance's receive socket. liblcm keeps its socket to
 * itself (lcm_get_fileno is a notification pipe), so a process that must act
 * on it (the recorder reads its kernel drops, the channel filter attaches a
 * program to it) looks among its own descriptors for a UDP socket bound to
 * the URL's port. */
#ifndef AUV_LCM_SOCKET_H
#define AUV_LCM_SOCKET_H

#include <stddef.h>
#include <sys/types.h>

/* The port of a udpm URL: 7667 when it names none; url NULL or empty is
 * LCM_DEFAULT_URL, else liblcm's default (udpm on 7667). -1 for another
 * provider or a port out of range. */
int lcm_url_port(const char *url);

/* A udpm url's group (dotted quad), port and recv_buf_size (0 when it names
 * none), with the defaults above (group 239.255.76.67). 0, or -1 for another
 * provider or a malformed address. */
int lcm_udpm_url_parse(const char *url, char *group, size_t group_len, int *port, long *recv_buf);

/* Calls fn(fd, inode, user) for every UDP socket of this process bound to
 * port, until fn returns non-zero. 0, or -1 when /proc/self/fd cannot be read. */
int lcm_sockets_on_port(int port, int (*fn)(int fd, ino_t inode, void *user), void *user);

#endif
