/* Typed LCM subscriptions that count and drop bad messages.
 *
 * lcm-gen's own *_subscribe() prints to stderr and carries on when a message
 * fails to decode, so a broken publisher is only visible in a terminal. This
 * helper checks the fingerprint, decodes with the type's decode function,
 * and counts every failure per subscription (wrong fingerprint, truncated or
 * otherwise malformed payload) so managers can publish the counts in their
 * status and health messages. A bad message never reaches the handler and
 * never ends the receive loop. */
#ifndef AUV_LCM_RX_H
#define AUV_LCM_RX_H

#include <stdint.h>

#include <lcm/lcm.h>

#include "common/auv_types.h"

typedef struct {
    uint64_t received;          /* every message on the channel */
    uint64_t delivered;         /* decoded and handed to the handler */
    uint64_t wrong_fingerprint; /* another type, or garbage */
    uint64_t malformed;         /* right type, but truncated or corrupt */
} rx_stats_t;

/* msg is the decoded struct (e.g. auv_nav_solution_t *); it is freed after
 * the handler returns, so copy what must be kept. */
typedef void (*rx_handler_t)(const char *channel, const void *msg, int64_t recv_utime, void *user);

typedef struct rx_sub rx_sub_t;
typedef struct rx_raw rx_raw_t;

/* lcm_create(url) whose receiving this module does: on a udpm url it reads
 * the group on a socket of its own (one wake-up per datagram instead of
 * liblcm's two: lcm_rx_own.c), with a kernel-side channel filter
 * (lcm_chanfilter.h) built from its subscriptions, so the process wakes only
 * for its own channels. Publish on it with liblcm as usual; receive with
 * rx_handle_timeout, subscribe only through rx_subscribe and
 * rx_subscribe_raw. AUV_LCM_READER=0 leaves receiving to liblcm (its socket
 * still filtered; AUV_LCM_CHANFILTER=0 turns the filter off). Close it with
 * rx_lcm_destroy. */
lcm_t *rx_lcm_create(const char *url);
void rx_lcm_destroy(lcm_t *lcm);

/* lcm_handle_timeout for any instance: handles one message (1), or none
 * within timeout_ms (0; also when a signal interrupted the wait), -1 on a
 * receive error. */
int rx_handle_timeout(lcm_t *lcm, int timeout_ms);

/* A subscription with liblcm's raw handler. */
rx_raw_t *rx_subscribe_raw(lcm_t *lcm, const char *channel, lcm_msg_handler_t handler, void *user);

/* rx_subscribe_raw for the messages that carry payload_len bytes of payload
 * at payload_at of their encoding (0: the fingerprint): the kernel drops the
 * others before the process wakes, where the filter is on. The handler must
 * still check: without a filter (another transport, AUV_LCM_CHANFILTER=0)
 * every message of the channel arrives. */
rx_raw_t *rx_subscribe_raw_where(lcm_t *lcm, const char *channel, const void *payload, int payload_at,
                                 int payload_len, lcm_msg_handler_t handler, void *user);
void rx_unsubscribe_raw(lcm_t *lcm, rx_raw_t *raw);
/* liblcm's subscription queue (its default is 30); nothing to size on an own
 * socket, whose queue is the kernel's receive buffer. 0 ok. */
int rx_raw_set_queue_capacity(rx_raw_t *raw, int capacity);

/* Subscribe to channel (an LCM regex) expecting one type. NULL on failure. */
rx_sub_t *rx_subscribe(lcm_t *lcm, const char *channel, const auv_type_entry_t *type,
                       rx_handler_t handler, void *user);
void rx_unsubscribe(lcm_t *lcm, rx_sub_t *sub);

/* How many undelivered messages LCM queues for this subscription before it
 * drops new ones (liblcm's default is 30). Returns lcm's result (0 ok). */
int rx_set_queue_capacity(rx_sub_t *sub, int capacity);

/* A subscription to a channel pattern that carries several types (a tool
 * listening to `AUV1\..*` for one type) sees the others as a matter of
 * course: count them as wrong_fingerprint without printing each one. */
void rx_set_quiet_other_types(rx_sub_t *sub, int quiet);

/* Inside a handler: the received bytes of the message being handled (exactly
 * the encoded message, fingerprint first: rx_decode refuses any byte more or
 * less). Valid until the handler returns; NULL outside a handler. */
const void *rx_current_raw(const rx_sub_t *sub, size_t *len);

const rx_stats_t *rx_stats(const rx_sub_t *sub);
uint64_t rx_decode_errors(const rx_sub_t *sub);

/* Decode one buffer as the given type into out (struct_size bytes), checking
 * the fingerprint first. Returns 0 on success, -1 wrong fingerprint,
 * -2 malformed. On success the caller owns out and must call
 * type->info()->decode_cleanup(out). Exposed for tests and log readers. */
int rx_decode(const auv_type_entry_t *type, const void *data, int len, void *out);

#endif
