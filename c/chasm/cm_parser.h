/* Parser: plan text (and its includes) -> cm_aplan. Errors are collected;
 * after an error the parser skips to the end of the statement and goes on. */
#ifndef CM_PARSER_H
#define CM_PARSER_H
#include <stddef.h>

#include "chasm/chasm.h"
#include "chasm/cm_arena.h"
#include "chasm/cm_ast.h"
#include "chasm/cm_diag.h"

typedef struct {
    cm_arena *arena;
    cm_diag *diag;
    cm_aplan *plan;
    int file_counter;
    const char *stack[CHASM_MAX_INCLUDE_DEPTH + 1];   /* files being included, for cycle detection */
    int depth;
} cm_parse_ctx;

/* name: shown in errors; dir: where relative includes are looked up. */
void cm_parse_text(cm_parse_ctx *p, const char *name, const char *dir, const char *text, size_t len,
                   cm_loc *include_loc);
/* Reads and parses a file; errors at include_loc (or position 0:0) if unreadable. */
void cm_parse_file(cm_parse_ctx *p, const char *path, cm_loc *include_loc);
/* Is s a reserved word of the language? */
int cm_is_keyword(const char *s);
#endif
