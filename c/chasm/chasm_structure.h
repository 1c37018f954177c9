/* chasm_structure.h: what a loaded plan is made of, for views that draw it
 * (the managers publish it as auv.chasm_structure_t, docs/console.md).
 *
 * States are numbered 0 .. chasm_state_count()-1, parents before children.
 * Transitions are numbered the same way every time: the plan's root-level
 * aborts first, then each state's own in declaration order. The getters do
 * not allocate (chasm_lint and chasm_outline_file do, for their own use);
 * strings live as long as the machine. */
#ifndef CHASM_STRUCTURE_H
#define CHASM_STRUCTURE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "chasm/chasm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where a state, action or transition was written. */
typedef struct {
    const char *file;
    int line, col;
} chasm_where;

typedef struct {
    const char *name, *path;
    int parent, default_child, next;   /* state numbers, -1: none */
    bool next_done;                    /* `next done` */
    int n_actions, n_transitions;
    chasm_where where;
} chasm_state_info;

typedef struct {
    const char *text;                  /* "set setpoint.depth", "goto" */
    const char *time_model;            /* "entry", "exit", "cycle", "every", "after" */
    double period_s;                   /* every / after */
    chasm_where where;
} chasm_action_info;

#define CHASM_TRANS_MAX_TESTS 64       /* tests named in one condition, as reported */
typedef struct {
    int from, to;                      /* from -1: a root-level abort */
    int history;                       /* 0 none, 1 resume, 2 resume deep */
    const char *condition;
    int n_tests;                       /* tests named in the condition (at most CHASM_TRANS_MAX_TESTS) */
    const char *test_name[CHASM_TRANS_MAX_TESTS];
    chasm_where where;
} chasm_trans_info;

const char *chasm_plan_name(const chasm_machine *m);   /* as loaded: a path or a LOAD_PLAN name */
int chasm_initial_state(const chasm_machine *m);
/* 0, or -1 on a number out of range. */
int chasm_state_info_get(const chasm_machine *m, int state, chasm_state_info *out);
int chasm_action_info_get(const chasm_machine *m, int state, int k, chasm_action_info *out);
/* state -1: the k-th root-level abort. */
int chasm_trans_info_get(const chasm_machine *m, int state, int k, chasm_trans_info *out);
int chasm_abort_count(const chasm_machine *m);

/* The parameters (the definition that won: the outermost file's, or -D's). */
size_t chasm_param_count(const chasm_machine *m);
/* Name and the value as written ("12 m", "\"text\"", "true") into buf. */
const char *chasm_param_get(const chasm_machine *m, size_t i, char *buf, size_t cap);

/* The current value of every test named in the transitions that can fire now,
 * in the order above: the aborts' tests, then for each active state, root
 * first, its transitions' tests. Writes at most cap; returns how many there are. */
int chasm_live_tests(const chasm_machine *m, bool *out, int cap);

/* A variable's value as a number: bools 0/1, NaN for strings, messages and a
 * variable that never had a value. */
double chasm_var_number(const chasm_machine *m, int id);

/* Deeper checks than loading (`chasm check`, docs/chasm.md "Checks"): each
 * finding with its place, a kind ("unreachable", "never-fires", "no-way-out",
 * "unwritten-output", "shadowed-abort") and a sentence. The number found. */
typedef void (*chasm_finding_fn)(void *user, chasm_where where, const char *kind, const char *message);
int chasm_lint(const chasm_machine *m, chasm_finding_fn fn, void *user);

/* The states of a plan file as parsed, whether or not it loads (a plan
 * author's view: `chasm outline`): fn gets each state, parents first, with
 * its number, its parent's (-1 for a root), its path and place. The count. */
typedef void (*chasm_outline_fn)(void *user, int index, int parent, const char *path, chasm_where where);
int chasm_outline_file(const char *path, chasm_outline_fn fn, void *user);

#ifdef __cplusplus
}
#endif
#endif
