#include "tm_lines.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(char *why, size_t whylen, const char *s, const char *p, const char *msg)
{
    snprintf(why, whylen, "at character %d: %s", (int)(p - s) + 1, msg);
    return -1;
}

static const char *skip_ws(const char *p)
{
    while (*p == ' ' || *p == '\t')
        p++;
    return p;
}

int tm_roster_parse(tm_roster *r, const char *s, char *why, size_t whylen)
{
    memset(r, 0, sizeof *r);
    const char *p = s;
    for (;;) {
        p = skip_ws(p);
        const char *b = p;
        while (isalnum((unsigned char)*p) || *p == '_' || *p == '-')
            p++;
        size_t len = (size_t)(p - b);
        if (len == 0)
            return fail(why, whylen, s, p, "expected a vehicle name (letters, digits, _ or -)");
        if (len >= TM_NAME_LEN)
            return fail(why, whylen, s, b, "vehicle name too long (max 23 characters)");
        if (r->n >= TM_MAX_TEAM)
            return fail(why, whylen, s, b, "more than 16 vehicles (the link's vehicle field is 4 bits)");
        memcpy(r->name[r->n], b, len);
        for (int i = 0; i < r->n; i++)
            if (!strcmp(r->name[i], r->name[r->n]))
                return fail(why, whylen, s, b, "vehicle named twice");
        r->n++;
        p = skip_ws(p);
        if (*p == '\0')
            return 0;
        if (*p != ',')
            return fail(why, whylen, s, p, "expected ',' between vehicle names");
        p++;
    }
}

int tm_roster_index(const tm_roster *r, const char *name)
{
    for (int i = 0; i < r->n; i++)
        if (!strcmp(r->name[i], name))
            return i;
    return -1;
}

static int number(const char *s, const char **p, double *v, char *why, size_t whylen)
{
    *p = skip_ws(*p);
    char *end;
    errno = 0;
    *v = strtod(*p, &end);
    if (end == *p || errno || !(*v >= -1e6 && *v <= 1e6))
        return fail(why, whylen, s, *p, "expected a coordinate in metres (within +-1e6)");
    *p = end;
    return 0;
}

static int point(const char *s, const char **p, gd_point *pt, char *why, size_t whylen)
{
    if (number(s, p, &pt->n, why, whylen))
        return -1;
    *p = skip_ws(*p);
    if (**p != ',')
        return fail(why, whylen, s, *p, "expected ',' between north and east");
    (*p)++;
    return number(s, p, &pt->e, why, whylen);
}

int tm_lines_parse(tm_lines *l, const char *s, int n_team, char *why, size_t whylen)
{
    memset(l, 0, sizeof *l);
    int max_owner = n_team > 0 ? n_team : TM_MAX_TEAM;
    const char *p = s;
    for (;;) {
        p = skip_ws(p);
        if (!isdigit((unsigned char)*p))
            return fail(why, whylen, s, p, "expected 'owner: north,east north,east' (owner = team index)");
        const char *b = p;
        long owner = strtol(p, (char **)&p, 10);
        if (owner >= max_owner)
            return fail(why, whylen, s, b, "owner is not a team index (the roster is shorter)");
        if (l->n >= TM_MAX_LINES)
            return fail(why, whylen, s, b, "more than 64 lines");
        p = skip_ws(p);
        if (*p != ':')
            return fail(why, whylen, s, p, "expected ':' after the owner");
        p++;
        tm_line *ln = &l->l[l->n];
        ln->owner = (int)owner;
        if (point(s, &p, &ln->a, why, whylen) || point(s, &p, &ln->b, why, whylen))
            return -1;
        l->n++;
        p = skip_ws(p);
        if (*p == '\0')
            return 0;
        if (*p != ';')
            return fail(why, whylen, s, p, "expected ';' between lines");
        p++;
        if (*skip_ws(p) == '\0')
            return 0;   /* a trailing ';' */
    }
}

int tm_is_searcher(const tm_lines *l, int v)
{
    for (int i = 0; i < l->n; i++)
        if (l->l[i].owner == v)
            return 1;
    return 0;
}

int tm_own_lines(const tm_lines *l, int v, int *out, int max)
{
    int k = 0;
    for (int i = 0; i < l->n && k < max; i++)
        if (l->l[i].owner == v)
            out[k++] = i;
    return k;
}

void tm_work_init(tm_work *w, const tm_lines *l, int n_team)
{
    memset(w, 0, sizeof *w);
    for (int v = 0; v < TM_MAX_TEAM; v++)
        w->n[v] = v < n_team ? tm_own_lines(l, v, w->line[v], TM_MAX_LINES) : 0;
}

int tm_takeover_deal(tm_work *w, const tm_lines *l, int lost, int from, const int *alive, int n_team,
                     int to[TM_MAX_LINES])
{
    int surv[TM_MAX_TEAM], ns = 0;
    for (int v = 0; v < n_team && v < TM_MAX_TEAM; v++)
        if (v != lost && alive[v] && tm_is_searcher(l, v))
            surv[ns++] = v;
    for (int i = 0; i < TM_MAX_LINES; i++)
        to[i] = -1;
    if (ns == 0 || lost < 0 || lost >= TM_MAX_TEAM)
        return 0;
    int dealt = 0;
    for (int k = from < 0 ? 0 : from; k < w->n[lost]; k++) {
        int line = w->line[lost][k], v = surv[dealt++ % ns];
        to[line] = v;
        if (w->n[v] < TM_MAX_LINES)
            w->line[v][w->n[v]++] = line;
    }
    return dealt;
}
