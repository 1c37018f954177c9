/* The recorder's health on SIM.HEALTH (process_health_t, a shared process:
 * vehicle ""): messages received, and in queue_overflows everything lost so
 * far - dropped from its own queue plus missed (kernel socket drops). */
#ifndef REC_HEALTH_H
#define REC_HEALTH_H

#include <lcm/lcm.h>
#include <stdint.h>

typedef struct {
    double last_wall, last_cpu;
} rec_health;

void rec_health_init(rec_health *h);
void rec_health_publish(rec_health *h, lcm_t *lcm, const char *name, int64_t utime,
                        int64_t received, int64_t lost);

#endif
