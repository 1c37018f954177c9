/* What the kernel did with the recorder's LCM receive socket. liblcm keeps
 * its socket to itself, so it is found among the process's descriptors (a
 * UDP socket bound to the URL's port): its granted receive buffer
 * (SO_RCVBUF) and the datagrams the kernel dropped because that buffer was
 * full (the `drops` column of /proc/self/net/udp) - messages the recorder
 * missed before it could see them. */
#ifndef REC_SOCKET_H
#define REC_SOCKET_H

#include <stdint.h>

typedef struct {
    int fd;                     /* -1: not found */
    unsigned long inode;
    int granted_bytes;          /* SO_RCVBUF as the kernel reports it */
} rec_socket;

/* The port of a udpm URL (7667 when it names none); -1 for other providers. */
int rec_url_port(const char *url);
/* 0 when found. */
int rec_socket_find(rec_socket *s, int port);
/* Kernel drops on that socket so far; -1 when they cannot be read. */
int64_t rec_socket_drops(const rec_socket *s);
/* net.core.rmem_max, the cap on what a process may ask; -1 unknown. */
long rec_rmem_max(void);

#endif
