/* The states of a plan as parsed, even when it does not load
 * (chasm_outline_file in chasm_structure.h): an author's view shows the tree
 * with each load error beside the state it concerns. */
#include <stdio.h>
#include <string.h>

#include "chasm/chasm_structure.h"
#include "chasm/cm_arena.h"
#include "chasm/cm_parser.h"

static int walk(const cm_astate *s, int parent, const char *prefix, int *next, chasm_outline_fn fn, void *user)
{
    for (; s; s = s->next) {
        int me = (*next)++;
        char path[1024];
        snprintf(path, sizeof path, "%s%s%s", prefix, *prefix ? "/" : "", s->name ? s->name : "?");
        fn(user, me, parent, path, (chasm_where){s->loc.file ? s->loc.file : "", s->loc.line, s->loc.col});
        walk(s->children, me, path, next, fn, user);
    }
    return *next;
}

int chasm_outline_file(const char *path, chasm_outline_fn fn, void *user)
{
    cm_arena arena;
    memset(&arena, 0, sizeof arena);
    cm_diag d = {0};
    d.limit = 500;
    cm_aplan *plan = cm_alloc(&arena, sizeof *plan);
    cm_parse_ctx pc = {.arena = &arena, .diag = &d, .plan = plan};
    cm_parse_file(&pc, cm_strdup(&arena, path), NULL);
    int next = 0;
    walk(plan->roots, -1, "", &next, fn, user);
    cm_diag_free(&d);
    cm_arena_free(&arena);
    return next;
}
