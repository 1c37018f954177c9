/* Why a driver dropped bytes or frames: a count per reason ("bad checksum",
 * "latitude out of range", ...), published in driver_status_t, their total in
 * process_health_t.decode_errors. The first drop of each reason is logged on
 * stderr once, like every drop in the project (docs/channels.md, "Time and
 * timestamps", rule 5); further drops of that reason are only counted. */
#ifndef DRV_REASONS_H
#define DRV_REASONS_H

#include <stdint.h>

#define DRV_MAX_REASONS 48
#define DRV_REASON_LEN 48

typedef struct {
    char name[DRV_MAX_REASONS][DRV_REASON_LEN];
    int64_t count[DRV_MAX_REASONS];
    int n;
    int64_t total;
    int64_t overflow; /* drops of reasons beyond DRV_MAX_REASONS: counted as "other" */
} drv_reasons;

void drv_reasons_init(drv_reasons *r);
/* Counts one drop of `reason`; returns 1 when it is the first of its kind
 * (the caller logs it), 0 otherwise. */
int drv_reasons_count(drv_reasons *r, const char *reason);
/* The count of one reason (0 if never seen). */
int64_t drv_reasons_get(const drv_reasons *r, const char *reason);

#endif
