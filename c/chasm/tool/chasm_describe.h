#ifndef CHASM_DESCRIBE_H
#define CHASM_DESCRIBE_H
#include <stddef.h>
/* Prints a plugin's behaviors, test handlers and parameter schemas. 0 or 1. */
int chasm_describe(const char *const *dirs, size_t n_dirs, const char *name);
#endif
