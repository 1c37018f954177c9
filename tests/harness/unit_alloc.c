/* The malloc & co. wrappers that count allocations (unit_alloc.h). */
#include "unit_alloc.h"

long unit_allocs;

void *__wrap_malloc(size_t n)
{
    unit_allocs++;
    return __real_malloc(n);
}

void *__wrap_calloc(size_t n, size_t k)
{
    unit_allocs++;
    return __real_calloc(n, k);
}

void *__wrap_realloc(void *p, size_t n)
{
    unit_allocs++;
    return __real_realloc(p, n);
}
