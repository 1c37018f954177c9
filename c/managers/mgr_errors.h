/* Load errors (plan and bindings) collected as lines "file:line:col: message":
 * printed to stderr as they come, and kept so a rejected LOAD_PLAN's ack can
 * quote them. */
#ifndef MGR_ERRORS_H
#define MGR_ERRORS_H

#include <stddef.h>

typedef struct {
    char **lines;
    size_t n;
    int quiet;          /* only collect, do not print (the fuzzer) */
} mgr_errors;

/* Adds one line (and prints it). e may be NULL: then it is only printed. */
void mgr_errors_add(mgr_errors *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* "N errors: first; second; ... (and K more)" in at most cap bytes, quoting
 * at most max_quoted lines. */
void mgr_errors_summary(const mgr_errors *e, size_t max_quoted, char *out, size_t cap);
void mgr_errors_free(mgr_errors *e);

#endif
