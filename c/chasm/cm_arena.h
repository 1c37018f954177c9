/* Bump allocator: every object of a loaded machine lives in one arena, so a
 * load that fails half-way frees everything at once and nothing leaks. */
#ifndef CM_ARENA_H
#define CM_ARENA_H
#include <stddef.h>

typedef struct cm_arena_block cm_arena_block;
typedef struct {
    cm_arena_block *head;
} cm_arena;

void *cm_alloc(cm_arena *a, size_t size);          /* zeroed, 16-byte aligned; aborts on OOM */
char *cm_strdup(cm_arena *a, const char *s);
char *cm_strndup(cm_arena *a, const char *s, size_t n);
char *cm_sprintf(cm_arena *a, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void cm_arena_free(cm_arena *a);
#endif
