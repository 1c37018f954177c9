#include "chasm/cm_diag.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void cm_error(cm_diag *d, cm_loc loc, const char *fmt, ...)
{
    if (d->limit && d->len >= d->limit) return;

    if (d->len == d->cap) {
        d->cap = d->cap ? d->cap * 2 : 16;
        d->items = realloc(d->items, d->cap * sizeof *d->items);
        if (!d->items) abort();
    }
    char msg[1024];
    if (d->limit && d->len + 1 == d->limit) {
        /* the last place says that the list stops here: never a silent cut */
        snprintf(msg, sizeof msg, "too many errors: only the first %zu are shown", d->limit - 1);
    } else {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
    }
    size_t n = strlen(msg) + strlen(loc.file ? loc.file : "?") + 64;
    char *text = malloc(n);
    if (!text) abort();
    snprintf(text, n, "%s:%d:%d: error: %s", loc.file ? loc.file : "?", loc.line, loc.col, msg);
    d->items[d->len] = (cm_diag_entry){loc, text, d->len};
    d->len++;
}

static int cmp_entry(const void *a, const void *b)
{
    const cm_diag_entry *x = a, *y = b;
    if (x->loc.file_order != y->loc.file_order) return x->loc.file_order < y->loc.file_order ? -1 : 1;
    if (x->loc.line != y->loc.line) return x->loc.line < y->loc.line ? -1 : 1;
    if (x->loc.col != y->loc.col) return x->loc.col < y->loc.col ? -1 : 1;
    return x->seq < y->seq ? -1 : (x->seq > y->seq);
}

void cm_diag_sort(cm_diag *d)
{
    if (d->len > 1) qsort(d->items, d->len, sizeof *d->items, cmp_entry);
}

void cm_diag_free(cm_diag *d)
{
    for (size_t i = 0; i < d->len; i++) free(d->items[i].text);
    free(d->items);
    memset(d, 0, sizeof *d);
}

/* Damerau-lite Levenshtein, bounded to short words (names are short). */
static int edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 63 || lb > 63) return 99;
    int prev[64], cur[64];
    for (size_t j = 0; j <= lb; j++) prev[j] = (int)j;
    for (size_t i = 1; i <= la; i++) {
        cur[0] = (int)i;
        for (size_t j = 1; j <= lb; j++) {
            int c = prev[j - 1] + (a[i - 1] != b[j - 1]);
            if (prev[j] + 1 < c) c = prev[j] + 1;
            if (cur[j - 1] + 1 < c) c = cur[j - 1] + 1;
            cur[j] = c;
        }
        memcpy(prev, cur, sizeof(int) * (lb + 1));
    }
    return prev[lb];
}

void cm_suggest_init(cm_suggest *s, const char *word)
{
    s->word = word;
    s->best = NULL;
    s->best_dist = 1000;
}

void cm_suggest_add(cm_suggest *s, const char *cand)
{
    if (!cand || !strcmp(cand, s->word)) return;
    int d = edit_distance(s->word, cand);
    int len = (int)strlen(s->word);
    int limit = len <= 3 ? 1 : len <= 6 ? 2 : 3;
    if (d <= limit && d < s->best_dist) {
        s->best = cand;
        s->best_dist = d;
    }
}

const char *cm_suggest_hint(const cm_suggest *s, char *buf, size_t len)
{
    if (!s->best) return "";
    snprintf(buf, len, " (did you mean '%s'?)", s->best);
    return buf;
}
