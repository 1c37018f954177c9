/* Inside lcm_rx: one raw subscription, and the instances that read the udpm
 * group on a socket of their own (lcm_rx_own.c) instead of through liblcm's
 * receive thread. Not for other callers: lcm_rx.h is the interface. */
#ifndef AUV_LCM_RX_ROUTE_H
#define AUV_LCM_RX_ROUTE_H

#include <lcm/lcm.h>
#include <regex.h>

typedef struct rx_own rx_own_t;

struct rx_raw {
    lcm_subscription_t *lcm_sub; /* through liblcm; NULL on an own socket */
    rx_own_t *own;               /* the own-socket instance, or NULL */
    lcm_msg_handler_t fn;
    void *user;
    char *pattern;
    regex_t re;                  /* "^(pattern)$", as lcm_subscribe anchors it */
    void *payload;               /* the kernel filter's payload condition (copied) */
    int payload_at, payload_len;
    int dead;                    /* unsubscribed while a message was being dispatched */
    struct rx_raw *next;
};

/* The own-socket instance of lcm (made by rx_lcm_create), or NULL. */
rx_own_t *rx_own_of(const lcm_t *lcm);
/* Makes one for lcm on url, unless url is not udpm or AUV_LCM_READER=0:
 * then NULL, and liblcm receives. */
rx_own_t *rx_own_create(lcm_t *lcm, const char *url);
void rx_own_destroy(lcm_t *lcm);

/* Adds or removes a route (the kernel filter follows, both ways). */
int rx_own_add(rx_own_t *own, struct rx_raw *r);
void rx_own_remove(rx_own_t *own, struct rx_raw *r);

/* lcm_handle_timeout for an own-socket instance. */
int rx_own_handle_timeout(rx_own_t *own, int timeout_ms);

#endif
