/* Graphviz view of a plan: composite states as clusters, default child in
 * bold, default next dashed, transitions labelled with their condition. */
#include <stdio.h>

#include "chasm/cm_machine.h"

static void esc(FILE *o, const char *s)
{
    for (; *s; s++) {
        if (*s == '"' || *s == '\\') fputc('\\', o);
        fputc(*s, o);
    }
}

/* Edges of clusters attach to an invisible anchor node inside them. */
static void node_id(FILE *o, const cm_state *s) { fprintf(o, "s%d", s->index); }

static void emit_state(FILE *o, const cm_state *s, int indent)
{
    if (s->first_child) {
        fprintf(o, "%*ssubgraph cluster_%d {\n%*s  label=\"", indent, "", s->index, indent, "");
        esc(o, s->name);
        fprintf(o, "\";\n%*s  s%d [shape=point, style=invis];\n", indent, "", s->index);
        for (const cm_state *c = s->first_child; c; c = c->next_sibling) emit_state(o, c, indent + 2);
        fprintf(o, "%*s}\n", indent, "");
    } else {
        fprintf(o, "%*ss%d [label=\"", indent, "", s->index);
        esc(o, s->name);
        fprintf(o, "\"];\n");
    }
}

void chasm_write_dot(const chasm_machine *m, FILE *o)
{
    fprintf(o, "digraph chasm {\n  compound=true;\n  node [shape=box, style=rounded];\n  label=\"");
    esc(o, m->plan_name ? m->plan_name : "plan");
    fprintf(o, "\";\n  start [shape=circle, label=\"\", width=0.2, style=filled, fillcolor=black];\n");
    for (int i = 0; i < m->n_states; i++)
        if (!m->states[i].parent) emit_state(o, &m->states[i], 2);
    fprintf(o, "  start -> ");
    node_id(o, m->initial);
    fprintf(o, ";\n");
    for (int i = 0; i < m->n_states; i++) {
        const cm_state *s = &m->states[i];
        if (s->default_child) {
            fprintf(o, "  s%d -> s%d [style=bold, arrowhead=odot, label=\"start\"];\n", s->index, s->default_child->index);
        }
        if (s->next) fprintf(o, "  s%d -> s%d [style=dashed, label=\"next\"];\n", s->index, s->next->index);
        for (int k = 0; k < s->n_trans; k++) {
            const cm_trans *t = &s->trans[k];
            fprintf(o, "  s%d -> s%d [label=\"", s->index, t->target->index);
            esc(o, t->history == HIST_DEEP ? "resume deep: " : t->history == HIST_SHALLOW ? "resume: " : "");
            esc(o, t->text);
            fprintf(o, "\"];\n");
        }
    }
    for (int k = 0; k < m->n_aborts; k++) {
        fprintf(o, "  abort%d [shape=octagon, label=\"abort\", color=red];\n  abort%d -> s%d [color=red, label=\"", k, k,
                m->aborts[k].target->index);
        esc(o, m->aborts[k].text);
        fprintf(o, "\"];\n");
    }
    fprintf(o, "}\n");
}
