#include "drivers/common/drv_reasons.h"

#include <string.h>

void drv_reasons_init(drv_reasons *r) { memset(r, 0, sizeof *r); }

int drv_reasons_count(drv_reasons *r, const char *reason)
{
    r->total++;
    for (int i = 0; i < r->n; i++)
        if (strncmp(r->name[i], reason, DRV_REASON_LEN - 1) == 0) {
            r->count[i]++;
            return 0;
        }
    /* a fixed table: a driver's reasons are a short, known list; the last
     * slot collects whatever does not fit, so no drop goes uncounted */
    int i = r->n < DRV_MAX_REASONS ? r->n++ : DRV_MAX_REASONS - 1;
    if (i == DRV_MAX_REASONS - 1 && r->n == DRV_MAX_REASONS && r->count[i] > 0) {
        strcpy(r->name[i], "other");
        r->count[i]++;
        r->overflow++;
        return 0;
    }
    strncpy(r->name[i], reason, DRV_REASON_LEN - 1);
    r->name[i][DRV_REASON_LEN - 1] = '\0';
    r->count[i] = 1;
    return 1;
}

int64_t drv_reasons_get(const drv_reasons *r, const char *reason)
{
    for (int i = 0; i < r->n; i++)
        if (strncmp(r->name[i], reason, DRV_REASON_LEN - 1) == 0)
            return r->count[i];
    return 0;
}
