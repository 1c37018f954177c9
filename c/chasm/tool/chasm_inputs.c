#include "chasm_inputs.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chasm/cm_lexer.h"
#include "chasm/cm_units.h"

static void push(chasm_inputs *in, chasm_input_event e)
{
    in->ev = realloc(in->ev, (in->n + 1) * sizeof *in->ev);
    if (!in->ev) abort();
    e.seq = in->n;
    in->ev[in->n++] = e;
}

static int cmp_ev(const void *a, const void *b)
{
    const chasm_input_event *x = a, *y = b;
    if (x->t_us != y->t_us) return x->t_us < y->t_us ? -1 : 1;
    return x->seq < y->seq ? -1 : x->seq > y->seq; /* same time: file order */
}

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long L = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)(L > 0 ? L : 0) + 1);
    if (!b) abort();
    *n = fread(b, 1, (size_t)(L > 0 ? L : 0), f);
    b[*n] = 0;
    fclose(f);
    return b;
}

/* number [unit] -> value in the unit `to` (NULL: seconds) */
/* Input times, like durations in plans: 0 to 1e9 s (no overflow in us). */
#define MAX_TIME_S 1e9
static int time_ok(double s) { return s >= 0 && s <= MAX_TIME_S; }

static int number(cm_token *t, size_t *i, const char *to, double *out, const char *path)
{
    int neg = 0;
    if (t[*i].type == T_MINUS) {
        neg = 1;
        (*i)++;
    }
    if (t[*i].type != T_NUMBER) {
        fprintf(stderr, "%s:%d:%d: error: expected a number\n", path, t[*i].line, t[*i].col);
        return -1;
    }
    double v = neg ? -t[*i].num : t[*i].num;
    int line = t[*i].line;
    (*i)++;
    const cm_unit *target = cm_unit_find(to ? to : "s");
    if (t[*i].type == T_IDENT && t[*i].line == line && strcmp(t[*i].text, "true") && strcmp(t[*i].text, "false")) {
        char u[64];
        snprintf(u, sizeof u, "%s", t[*i].text);
        int c = t[*i].col;
        /* a unit only if it is followed by more on the line or is a known unit */
        const cm_unit *un = NULL;
        size_t j = *i + 1;
        if (t[j].type == T_SLASH && t[j + 1].type == T_IDENT) {
            snprintf(u + strlen(u), sizeof u - strlen(u), "/%s", t[j + 1].text);
            j += 2;
        }
        un = cm_unit_find(u);
        if (un) {
            if (!target || un->dim != target->dim) {
                fprintf(stderr, "%s:%d:%d: error: unit '%s' does not fit '%s'\n", path, line, c, u,
                        to && *to ? to : "a plain number");
                return -1;
            }
            v = v * un->to_si / target->to_si;
            *i = j;
        } else if (!to) {
            /* the variable name follows the time: no unit written */
        } else {
            fprintf(stderr, "%s:%d:%d: error: unknown unit '%s'\n", path, line, c, u);
            return -1;
        }
    }
    *out = v;
    return 0;
}

static int read_lines(const char *path, const char *text, size_t n, const chasm_machine *m, chasm_inputs *out)
{
    cm_arena a = {0};
    cm_diag d = {0};
    cm_tokens tk = cm_lex(&a, &d, path, 0, text, n);
    int rc = d.len ? -1 : 0;
    for (size_t k = 0; k < d.len; k++) fprintf(stderr, "%s\n", d.items[k].text);
    cm_token *t = tk.toks;
    size_t i = 0;
    while (rc == 0 && t[i].type != T_EOF) {
        if (t[i].type == T_NEWLINE) {
            i++;
            continue;
        }
        double ts;
        const cm_token *tt = &t[i];
        if (number(t, &i, NULL, &ts, path)) {
            rc = -1;
            break;
        }
        if (!time_ok(ts)) {
            fprintf(stderr, "%s:%d:%d: error: an input's time must be between 0 s and %g s\n", path, tt->line, tt->col,
                    MAX_TIME_S);
            rc = -1;
            break;
        }
        if (t[i].type != T_IDENT) {
            fprintf(stderr, "%s:%d:%d: error: expected a variable name after the time\n", path, t[i].line, t[i].col);
            rc = -1;
            break;
        }
        int id = chasm_var_find(m, t[i].text);
        if (id < 0) {
            fprintf(stderr, "%s:%d:%d: error: the plan has no variable '%s'\n", path, t[i].line, t[i].col, t[i].text);
            rc = -1;
            break;
        }
        i++;
        if (t[i].type != T_ASSIGN) {
            fprintf(stderr, "%s:%d:%d: error: expected '='\n", path, t[i].line, t[i].col);
            rc = -1;
            break;
        }
        i++;
        chasm_input_event e = {(int64_t)(ts * 1e6 + (ts >= 0 ? 0.5 : -0.5)), id, chasm_var_type(m, id), 0, 0, NULL, 0};
        if (e.type == CHASM_BOOL) {
            if (t[i].type != T_IDENT || (strcmp(t[i].text, "true") && strcmp(t[i].text, "false"))) {
                fprintf(stderr, "%s:%d:%d: error: '%s' is bool: write true or false\n", path, t[i].line, t[i].col,
                        chasm_var_name(m, id));
                rc = -1;
                break;
            }
            e.b = t[i].text[0] == 't';
            i++;
        } else if (e.type == CHASM_STRING || e.type == CHASM_MESSAGES) {
            /* a message of a messages variable is given as its bytes, in quotes */
            if (t[i].type != T_STRING) {
                if (e.type == CHASM_MESSAGES) {
                    fprintf(stderr, "%s:%d:%d: error: '%s' is a messages variable: write a message's bytes in quotes\n",
                            path, t[i].line, t[i].col, chasm_var_name(m, id));
                    rc = -1;
                    break;
                }
                fprintf(stderr, "%s:%d:%d: error: '%s' is a string: write it in quotes\n", path, t[i].line, t[i].col,
                        chasm_var_name(m, id));
                rc = -1;
                break;
            }
            e.s = strdup(t[i].text);
            i++;
        } else {
            const cm_token *vt = &t[i];
            if (number(t, &i, chasm_var_unit(m, id), &e.d, path)) {
                rc = -1;
                break;
            }
            if (e.type == CHASM_INT && !(e.d >= -9.0e18 && e.d <= 9.0e18)) {
                fprintf(stderr, "%s:%d:%d: error: '%s' is an int: %g is out of its range\n", path, vt->line, vt->col,
                        chasm_var_name(m, id), e.d);
                rc = -1;
                break;
            }
        }
        push(out, e);
        if (t[i].type != T_NEWLINE && t[i].type != T_EOF) {
            fprintf(stderr, "%s:%d:%d: error: expected the end of the line\n", path, t[i].line, t[i].col);
            rc = -1;
        }
    }
    free(tk.toks);
    cm_diag_free(&d);
    cm_arena_free(&a);
    return rc;
}

static int read_csv(const char *path, char *text, const chasm_machine *m, chasm_inputs *out)
{
    int cols[256], nc = 0, line = 0, header = 1;
    for (char *save = NULL, *ln = strtok_r(text, "\n", &save); ln; ln = strtok_r(NULL, "\n", &save)) {
        line++;
        if (ln[0] == '#' || ln[0] == '\r' || !ln[0]) continue;
        char *save2 = NULL;
        int c = 0;
        double t = 0;
        for (char *f = strtok_r(ln, ",\r", &save2); f; f = strtok_r(NULL, ",\r", &save2), c++) {
            while (*f == ' ') f++;
            if (header) {
                if (c == 0) continue;
                if (nc >= 256) {
                    fprintf(stderr, "%s:%d:1: error: more than 256 columns\n", path, line);
                    return -1;
                }
                cols[nc] = chasm_var_find(m, f);
                if (cols[nc] < 0) {
                    fprintf(stderr, "%s:%d:1: error: the plan has no variable '%s'\n", path, line, f);
                    return -1;
                }
                nc++;
                continue;
            }
            char *end;
            double v = strtod(f, &end);
            if (c == 0) {
                t = v;
                if (!time_ok(t)) {
                    fprintf(stderr, "%s:%d:1: error: an input's time must be between 0 s and %g s\n", path, line,
                            MAX_TIME_S);
                    return -1;
                }
                continue;
            }
            if (c > nc || !*f) continue;
            int id = cols[c - 1];
            chasm_input_event e = {(int64_t)(t * 1e6 + 0.5), id, chasm_var_type(m, id), v, 0, NULL, 0};
            if (e.type == CHASM_INT && !(v >= -9.0e18 && v <= 9.0e18)) {
                fprintf(stderr, "%s:%d:1: error: '%s' is an int: %g is out of its range\n", path, line,
                        chasm_var_name(m, id), v);
                return -1;
            }
            if (e.type == CHASM_BOOL) e.b = !strcmp(f, "true") || !strcmp(f, "1");
            if (e.type == CHASM_STRING || e.type == CHASM_MESSAGES) e.s = strdup(f); /* a message: the field's bytes */
            push(out, e);
        }
        header = 0;
    }
    return 0;
}

int chasm_inputs_read(const char *path, const chasm_machine *m, chasm_inputs *out)
{
    memset(out, 0, sizeof *out);
    size_t n = 0;
    char *text = slurp(path, &n);
    if (!text) {
        fprintf(stderr, "%s: error: cannot read the inputs file\n", path);
        return -1;
    }
    const char *p = text;
    while (*p == '#' || *p == '\n' || *p == ' ') {
        if (*p == '#') while (*p && *p != '\n') p++;
        else p++;
    }
    const char *eol = strchr(p, '\n');
    const char *comma = strchr(p, ',');
    int rc = comma && (!eol || comma < eol) ? read_csv(path, text, m, out) : read_lines(path, text, n, m, out);
    free(text);
    if (out->n) qsort(out->ev, out->n, sizeof *out->ev, cmp_ev);
    return rc;
}

void chasm_inputs_free(chasm_inputs *in)
{
    for (size_t i = 0; i < in->n; i++) free(in->ev[i].s);
    free(in->ev);
    memset(in, 0, sizeof *in);
}
