/* Inputs held until their step's clock: see mgr_held.h. */
#include "managers/mgr_held.h"

#include <stdlib.h>
#include <string.h>

int mgr_held_push(mgr_held *h, void *binding, int64_t utime, const void *data, size_t len)
{
    if (h->n >= MGR_HELD_MAX) {
        h->overflow++;
        return -1;
    }
    if (h->n == h->cap) {
        size_t cap = h->cap ? 2 * h->cap : 16;
        mgr_held_msg *items = realloc(h->items, cap * sizeof *items);
        if (!items) {
            h->overflow++;
            return -1;
        }
        h->items = items;
        h->cap = cap;
    }
    unsigned char *copy = malloc(len ? len : 1);
    if (!copy) {
        h->overflow++;
        return -1;
    }
    memcpy(copy, data, len);
    h->items[h->n++] = (mgr_held_msg){binding, utime, len, copy};
    h->held++;
    return 0;
}

void mgr_held_release(mgr_held *h, int64_t now, mgr_held_apply apply, void *user)
{
    /* One pass in arrival order: released messages go, the ones kept close
     * up, still in arrival order. */
    size_t kept = 0;
    for (size_t i = 0; i < h->n; i++) {
        mgr_held_msg m = h->items[i];
        if (m.utime > now) {
            h->items[kept++] = m;
            continue;
        }
        apply(m.binding, m.utime, m.data, m.len, user);
        free(m.data);
    }
    h->n = kept;
}

void mgr_held_free(mgr_held *h)
{
    for (size_t i = 0; i < h->n; i++)
        free(h->items[i].data);
    free(h->items);
    memset(h, 0, sizeof *h);
}
