#include "chasm/cm_lexer.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

const char *cm_tok_name(cm_tok_type t)
{
    static const char *n[] = {"end of file", "end of line", "name", "number", "string",
                              "$parameter", "'{'", "'}'", "'('", "')'", "','", "'='", "':'",
                              "'->'", "'/'", "'=='", "'!='", "'<'", "'<='", "'>'", "'>='",
                              "'-'", "'+-'"};
    return n[t];
}

static int ident_start(int c) { return isalpha(c) || c == '_'; }
static int ident_char(int c) { return isalnum(c) || c == '_'; }

cm_tokens cm_lex(cm_arena *a, cm_diag *d, const char *file, int file_order, const char *s, size_t n)
{
    size_t cap = 256, len = 0;
    cm_token *t = malloc(cap * sizeof *t);
    if (!t) abort();
    int line = 1, paren = 0;
    size_t line_start = 0, i = 0;
    for (;;) {
        if (len + 1 >= cap) {
            cap *= 2;
            t = realloc(t, cap * sizeof *t);
            if (!t) abort();
        }
        while (i < n && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) i++;
        if (i < n && s[i] == '#')
            while (i < n && s[i] != '\n') i++;
        cm_token *k = &t[len];
        memset(k, 0, sizeof *k);
        k->line = line;
        k->col = (int)(i - line_start) + 1;
        k->start = s + i;
        if (i >= n) {
            k->type = T_EOF;
            len++;
            break;
        }
        char c = s[i];
        cm_loc loc = {file, file_order, line, k->col};
        if (c == '\n') {
            i++;
            line++;
            line_start = i;
            if (paren > 0 || (len && t[len - 1].type == T_NEWLINE) || len == 0) continue;
            k->type = T_NEWLINE;
            k->len = 1;
            len++;
            continue;
        }
        if (c == '\0') {
            cm_error(d, loc, "unexpected NUL byte");
            i++;
            continue;
        }
        if (ident_start((unsigned char)c) || (c == '$' && i + 1 < n && ident_start((unsigned char)s[i + 1]))) {
            size_t b = i + (c == '$');
            size_t e = b;
            for (;;) {
                while (e < n && ident_char((unsigned char)s[e])) e++;
                if (e + 1 < n && s[e] == '.' && ident_start((unsigned char)s[e + 1])) {
                    e++;
                    continue;
                }
                break;
            }
            k->type = c == '$' ? T_PARAM : T_IDENT;
            k->text = cm_strndup(a, s + b, e - b);
            k->len = (int)(e - i);
            i = e;
            len++;
            continue;
        }
        if (isdigit((unsigned char)c) || (c == '.' && i + 1 < n && isdigit((unsigned char)s[i + 1]))) {
            size_t e = i;
            while (e < n && isdigit((unsigned char)s[e])) e++;
            if (e < n && s[e] == '.') {
                e++;
                while (e < n && isdigit((unsigned char)s[e])) e++;
            }
            if (e < n && (s[e] == 'e' || s[e] == 'E')) {
                size_t f = e + 1;
                if (f < n && (s[f] == '+' || s[f] == '-')) f++;
                if (f < n && isdigit((unsigned char)s[f])) {
                    while (f < n && isdigit((unsigned char)s[f])) f++;
                    e = f;
                }
            }
            /* Any length: the whole number is converted (never cut). */
            char *num = cm_strndup(a, s + i, e - i);
            k->type = T_NUMBER;
            k->num = strtod(num, NULL);
            k->len = (int)(e - i);
            i = e;
            len++;
            continue;
        }
        if (c == '"') {
            size_t e = i + 1;
            /* As long as the line: limits on string values are checked
             * where they are used (CHASM_STRING_MAX), never by cutting here. */
            size_t lim = n - i;
            char *out = cm_alloc(a, 1 + lim);
            size_t o = 0;
            int closed = 0;
            while (e < n && s[e] != '\n') {
                if (s[e] == '"') {
                    closed = 1;
                    e++;
                    break;
                }
                if (s[e] == '\\' && e + 1 < n && s[e + 1] != '\n') e++;
                if (o < lim) out[o++] = s[e];
                e++;
            }
            out[o] = 0;
            if (!closed) cm_error(d, loc, "unterminated string (a string ends with '\"' on the same line)");
            k->type = T_STRING;
            k->text = out;
            k->len = (int)(e - i);
            i = e;
            len++;
            continue;
        }
        int two = i + 1 < n ? s[i + 1] : 0;
        cm_tok_type ty;
        int w = 1;
        switch (c) {
        case '{': ty = T_LBRACE; break;
        case '}': ty = T_RBRACE; break;
        case '(': ty = T_LPAREN; paren++; break;
        case ')': ty = T_RPAREN; if (paren > 0) paren--; break;
        case ',': ty = T_COMMA; break;
        case ':': ty = T_COLON; break;
        case '/': ty = T_SLASH; break;
        case '=': if (two == '=') { ty = T_EQ; w = 2; } else ty = T_ASSIGN; break;
        case '!': if (two == '=') { ty = T_NE; w = 2; } else goto bad; break;
        case '<': if (two == '=') { ty = T_LE; w = 2; } else ty = T_LT; break;
        case '>': if (two == '=') { ty = T_GE; w = 2; } else ty = T_GT; break;
        case '-': if (two == '>') { ty = T_ARROW; w = 2; } else ty = T_MINUS; break;
        case '+': if (two == '-') { ty = T_PLUSMINUS; w = 2; } else goto bad; break;
        default:
        bad:
            if ((unsigned char)c >= 0x80)
                cm_error(d, loc, "unexpected character (byte 0x%02x): plans are plain ASCII outside strings and comments", (unsigned char)c);
            else if (isprint((unsigned char)c))
                cm_error(d, loc, "unexpected character '%c'", c);
            else
                cm_error(d, loc, "unexpected control character (byte 0x%02x)", (unsigned char)c);
            i++;
            continue;
        }
        k->type = ty;
        k->len = w;
        i += (size_t)w;
        len++;
    }
    return (cm_tokens){t, len};
}
