/* Tokens of the plan language. Newlines end statements, except inside
 * parentheses so long argument lists can be wrapped. `#` starts a comment. */
#ifndef CM_LEXER_H
#define CM_LEXER_H
#include <stddef.h>

#include "chasm/cm_arena.h"
#include "chasm/cm_diag.h"

typedef enum {
    T_EOF, T_NEWLINE, T_IDENT, T_NUMBER, T_STRING, T_PARAM,
    T_LBRACE, T_RBRACE, T_LPAREN, T_RPAREN, T_COMMA, T_ASSIGN, T_COLON, T_ARROW,
    T_SLASH, T_EQ, T_NE, T_LT, T_LE, T_GT, T_GE, T_MINUS, T_PLUSMINUS
} cm_tok_type;

typedef struct {
    cm_tok_type type;
    int line, col;
    const char *start;
    int len;
    double num;         /* T_NUMBER */
    char *text;         /* T_IDENT, T_PARAM (without $), T_STRING (unescaped) */
} cm_token;

typedef struct {
    cm_token *toks;
    size_t len;
} cm_tokens;

/* Lexes the whole text; errors go to diag, bad characters are skipped. */
cm_tokens cm_lex(cm_arena *a, cm_diag *d, const char *file, int file_order, const char *text, size_t n);
const char *cm_tok_name(cm_tok_type t);
#endif
