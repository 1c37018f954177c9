#include "chasm/cm_arena.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct cm_arena_block {
    cm_arena_block *next;
    size_t used, cap;
    _Alignas(16) unsigned char data[];
};

void *cm_alloc(cm_arena *a, size_t size)
{
    size = (size + 15u) & ~(size_t)15u;
    if (!size) size = 16;
    cm_arena_block *b = a->head;
    if (!b || b->cap - b->used < size) {
        size_t cap = size > 65536 ? size : 65536;
        b = malloc(sizeof *b + cap);
        if (!b) {
            fputs("chasm: out of memory\n", stderr);
            abort();
        }
        b->used = 0;
        b->cap = cap;
        b->next = a->head;
        a->head = b;
    }
    void *p = b->data + b->used;
    b->used += size;
    memset(p, 0, size);
    return p;
}

char *cm_strndup(cm_arena *a, const char *s, size_t n)
{
    char *p = cm_alloc(a, n + 1);
    memcpy(p, s, n);
    p[n] = 0;
    return p;
}

char *cm_strdup(cm_arena *a, const char *s) { return cm_strndup(a, s, strlen(s)); }

char *cm_sprintf(cm_arena *a, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *p = cm_alloc(a, (size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(p, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return p;
}

void cm_arena_free(cm_arena *a)
{
    cm_arena_block *b = a->head;
    while (b) {
        cm_arena_block *n = b->next;
        free(b);
        b = n;
    }
    a->head = NULL;
}
