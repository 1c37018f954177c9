/* What the kernel did with the recorder's receive socket (the one that takes
 * every datagram: rec_input.h): its granted receive buffer (SO_RCVBUF) and
 * the datagrams the kernel dropped because that buffer was full (the `drops`
 * column of /proc/self/net/udp) - messages the recorder missed before it
 * could see them. */
#ifndef REC_SOCKET_H
#define REC_SOCKET_H

#include <stdint.h>

typedef struct {
    int fd;                     /* -1: not found */
    unsigned long inode;
    int granted_bytes;          /* SO_RCVBUF as the kernel reports it */
} rec_socket;

/* Takes the socket fd; -1 when there is none (fd < 0: liblcm receives). */
int rec_socket_of(rec_socket *s, int fd);
/* Kernel drops on that socket so far; -1 when they cannot be read. */
int64_t rec_socket_drops(const rec_socket *s);
/* net.core.rmem_max, the cap on what a process may ask; -1 unknown. */
long rec_rmem_max(void);

#endif
