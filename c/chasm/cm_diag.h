/* Load errors: collected (never stop at the first), sorted by position and
 * formatted "file:line:col: error: message". Also the did-you-mean helper. */
#ifndef CM_DIAG_H
#define CM_DIAG_H
#include <stddef.h>

typedef struct {
    const char *file;   /* as the user named it; lives in the loader's arena */
    int file_order;     /* order files were opened: sorts includes after their includer's line */
    int line, col;
} cm_loc;

typedef struct {
    cm_loc loc;
    char *text;         /* malloc'd formatted line */
    size_t seq;
} cm_diag_entry;

typedef struct {
    cm_diag_entry *items;
    size_t len, cap;
    size_t limit;       /* stop collecting after this many (a fuzzed file can make millions) */
} cm_diag;

void cm_error(cm_diag *d, cm_loc loc, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
void cm_diag_sort(cm_diag *d);
void cm_diag_free(cm_diag *d);

/* Best candidate within a small edit distance of word, or NULL. */
typedef struct {
    const char *word;
    const char *best;
    int best_dist;
} cm_suggest;
void cm_suggest_init(cm_suggest *s, const char *word);
void cm_suggest_add(cm_suggest *s, const char *candidate);
/* " (did you mean 'x'?)" or "" */
const char *cm_suggest_hint(const cm_suggest *s, char *buf, size_t len);
#endif
