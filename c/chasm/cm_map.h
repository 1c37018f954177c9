/* String -> pointer hash map used only at load time (names of states, tests,
 * variables, params). Keys are not copied: they must outlive the map. */
#ifndef CM_MAP_H
#define CM_MAP_H
#include <stddef.h>

typedef struct {
    const char **keys;
    void **vals;
    size_t cap, len;
} cm_map;

void *cm_map_get(const cm_map *m, const char *key);
/* Returns the previous value (and keeps it) if key exists, else inserts and returns NULL. */
void *cm_map_put(cm_map *m, const char *key, void *val);
void cm_map_free(cm_map *m);
#endif
