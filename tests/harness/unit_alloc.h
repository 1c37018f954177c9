/* Allocation counting for the unit tests that prove a step or an update
 * allocates nothing. The program is linked with
 * -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc and unit_alloc.c: every
 * malloc, calloc and realloc of the code under test then passes through a
 * counter. C++ adds its operator new (tests/nav/unit/counted_new.cpp). */
#ifndef UNIT_ALLOC_H
#define UNIT_ALLOC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

extern long unit_allocs; /* allocations so far */

/* The C library's own, behind the wrappers (the linker names them). */
void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t k);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t k);
void *__wrap_realloc(void *p, size_t n);

#ifdef __cplusplus
}
#endif

#endif
