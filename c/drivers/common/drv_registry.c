/* The protocols linked into a program (each registers itself with
 * DRV_REGISTER): auv-driver-replay and the fuzzer serve every driver without
 * a list of them written anywhere. */
#include <strings.h>

#include "drivers/common/drv_protocol.h"

#define DRV_MAX_PROTOCOLS 32
static const drv_protocol *protocols[DRV_MAX_PROTOCOLS];
static int n_protocols;

void drv_register(const drv_protocol *p)
{
    if (n_protocols < DRV_MAX_PROTOCOLS)
        protocols[n_protocols++] = p;
}

const drv_protocol *drv_find(const char *device)
{
    for (int i = 0; i < n_protocols; i++)
        if (strcasecmp(protocols[i]->device, device) == 0)
            return protocols[i];
    return NULL;
}

int drv_count(void) { return n_protocols; }
const drv_protocol *drv_at(int i) { return i >= 0 && i < n_protocols ? protocols[i] : NULL; }
