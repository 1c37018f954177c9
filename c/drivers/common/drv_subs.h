/* A driver's LCM inputs (drv_protocol.subscriptions): each subscribed on
 * "<VEHICLE>.<suffix>" through the project's strict typed receive
 * (c/common/lcm_rx.h), its decoded messages handed to the protocol with the
 * driver's clock, its undecodable ones counted as the driver's drops. Apart
 * from drv_main.c so the framework's tests can drive it on an in-process LCM. */
#ifndef DRV_SUBS_H
#define DRV_SUBS_H

#include <lcm/lcm.h>
#include <stddef.h>
#include <stdint.h>

#include "common/lcm_rx.h"
#include "drivers/common/drv_clock.h"
#include "drivers/common/drv_protocol.h"

#define DRV_MAX_SUBS 8

typedef struct {
    const drv_subscription *spec;
    rx_sub_t *sub;
    uint64_t errors_counted; /* rx_decode_errors(sub) already counted as drops */
    char channel[128];
    char reason[DRV_REASON_LEN]; /* "undecodable ACTUATORS" */
    struct drv_subs *owner;
} drv_sub_binding;

typedef struct drv_subs {
    drv_sub_binding b[DRV_MAX_SUBS];
    int n;
    void *state;
    drv_ctx *ctx;
    const drv_clock *clock;
} drv_subs;

/* Subscribes every entry of p->subscriptions. 0, or -1 with a message in err
 * (an unknown type, too many entries, LCM refused). */
int drv_subs_init(drv_subs *s, lcm_t *lcm, const drv_protocol *p, void *state, drv_ctx *ctx, const drv_clock *clock,
                  char *err, size_t errlen);
/* After LCM handled messages: each new undecodable one becomes a drop. */
void drv_subs_account(drv_subs *s);
void drv_subs_close(drv_subs *s, lcm_t *lcm);

#endif
