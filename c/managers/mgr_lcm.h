/* LCM for a manager: URL from --lcm-url, else $LCM_DEFAULT_URL, else the
 * default, with a receive buffer sized for the largest LOAD_PLAN. */
#ifndef MGR_LCM_H
#define MGR_LCM_H

#include <stddef.h>

#include <lcm/lcm.h>

#include "managers/mgr_limits.h"

/* NULL on failure (printed). *max_plan_bytes: the plan size the buffer the
 * kernel granted can carry (MGR_MAX_PLAN_BYTES when it is large enough). */
lcm_t *mgr_lcm_open(const char *url_opt, const char *who, size_t *max_plan_bytes);

#endif
