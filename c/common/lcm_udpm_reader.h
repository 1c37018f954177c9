/* Reading an LCM udpm group on a socket of one's own, in batches.
 *
 * Why: liblcm receives on a thread of its own and hands each message to the
 * caller through a pipe, so every datagram costs two wake-ups (its thread,
 * then the caller). A process that takes every message of the world pays
 * them for each one: the recorder, about 270 messages per vehicle-second,
 * was a third of all the context switches of an 8-vehicle run
 * (docs/performance.md). On its own socket a process reads whatever has
 * queued with one recvmmsg call, when it chooses: one wake-up per batch.
 *
 * The wire format is LCM's UDP multicast protocol: short messages (LC02) and
 * fragmented ones (LC03), reassembled here per sender and sequence number.
 * Only reading: publishing stays with liblcm (a liblcm instance that never
 * subscribes makes no receive socket). Each datagram carries its kernel
 * receive time (SO_TIMESTAMP), so a batch read later keeps each message's
 * own receive stamp, and the kernel's drop count (SO_RXQ_OVFL). */
#ifndef AUV_LCM_UDPM_READER_H
#define AUV_LCM_UDPM_READER_H

#include <regex.h>
#include <stddef.h>
#include <stdint.h>

typedef struct lcm_udpm_reader lcm_udpm_reader_t;

/* One complete message: channel (NUL-terminated), payload, and the receive
 * time of its last datagram [us since the epoch, as liblcm's recv_utime]. */
typedef void (*lcm_udpm_handler)(const char *channel, const void *data, int len, int64_t recv_utime, void *user);

typedef struct {
    int64_t datagrams;          /* read from the socket */
    int64_t messages;           /* complete messages handed over */
    int64_t malformed;          /* not LCM, a header that does not add up, a channel empty or not UTF-8 */
    int64_t incomplete;         /* fragmented messages given up (a fragment lost) */
} lcm_udpm_counts;

/* 0 when AUV_LCM_READER=0 in the environment leaves receiving to liblcm. */
int lcm_udpm_reader_enabled(void);

/* Compiles a subscription pattern as lcm_subscribe means it: anchored at
 * both ends (POSIX extended syntax). 0, or regcomp's error code. */
int lcm_udpm_pattern_compile(regex_t *re, const char *pattern);

/* Opens a socket bound to the url's port and joined to its group (url NULL
 * or empty: LCM_DEFAULT_URL, else udpm://239.255.76.67:7667), with a receive
 * buffer of the url's recv_buf_size, else recv_buf bytes (0: the system's
 * default; the url: common/lcm_socket.h). NULL on failure, with the reason
 * in err. */
lcm_udpm_reader_t *lcm_udpm_reader_open(const char *url, long recv_buf, char *err, size_t errlen);
void lcm_udpm_reader_close(lcm_udpm_reader_t *r);

/* The socket, to poll() for readability, or to attach a channel filter to
 * (common/lcm_chanfilter.h, auv_chanfilter_attach). Non-blocking. */
int lcm_udpm_reader_fd(const lcm_udpm_reader_t *r);

/* One message, valid until the next call on the reader. */
typedef struct {
    const char *channel;
    const void *data;
    int len;
    int64_t recv_utime;
} lcm_udpm_msg;

/* The next message, without blocking: 1 (in m), 0 when nothing is queued,
 * -1 on a receive error (errno set). One at a time, so a caller that acts
 * between messages (a manager deciding a cycle after each) sees exactly the
 * order it would see through liblcm. */
int lcm_udpm_reader_next(lcm_udpm_reader_t *r, lcm_udpm_msg *m);
/* Datagrams read per system call (1..64, 64 by default). 1 for a caller
 * that polls the socket itself between messages (Python's select loops):
 * then the socket is readable exactly when a datagram waits. */
void lcm_udpm_reader_set_batch(lcm_udpm_reader_t *r, int n);
/* 1 when datagrams already read wait to be taken (poll would not see them). */
int lcm_udpm_reader_pending(const lcm_udpm_reader_t *r);

/* Hands every message queued on the socket now to fn, in arrival order,
 * without blocking. Returns the number of messages, -1 on a receive error
 * other than "nothing queued" (errno set). */
int lcm_udpm_reader_drain(lcm_udpm_reader_t *r, lcm_udpm_handler fn, void *user);

/* Datagrams the kernel dropped at this socket (its buffer was full), as of
 * the last datagram read; the receive buffer the kernel granted. */
int64_t lcm_udpm_reader_kernel_drops(const lcm_udpm_reader_t *r);
int lcm_udpm_reader_granted(const lcm_udpm_reader_t *r);
const lcm_udpm_counts *lcm_udpm_reader_counts(const lcm_udpm_reader_t *r);

#endif
