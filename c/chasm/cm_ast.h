/* Syntax tree of a plan (all files, includes expanded), built by the parser
 * in the loader's arena and consumed by the compile passes. */
#ifndef CM_AST_H
#define CM_AST_H
#include <stdbool.h>

#include "chasm/cm_diag.h"
#include "chasm/cm_units.h"

#include "chasm/chasm.h"
#define CM_MAX_PARSE_DEPTH CHASM_MAX_STATE_DEPTH

typedef enum { V_NONE, V_NUMBER, V_STRING, V_BOOL, V_PARAM, V_NAME } cm_vkind;

typedef struct {
    cm_vkind kind;
    cm_loc loc;
    double num;            /* as written, before unit conversion */
    const cm_unit *unit;   /* NULL: written without unit */
    bool is_int;           /* written without '.' or exponent */
    char *str;             /* string text, parameter name or variable name */
    bool b;
} cm_aval;

typedef struct cm_aarg {
    struct cm_aarg *next;
    char *name;
    cm_loc loc;
    cm_aval val;
} cm_aarg;

typedef enum { OP_LT, OP_LE, OP_GT, OP_GE, OP_EQ, OP_NE } cm_cmp;

typedef enum { CR_CMP, CR_WITHIN, CR_AGE, CR_ELAPSED, CR_BOOLVAR, CR_HANDLER } cm_crit_kind;

typedef struct {
    cm_crit_kind kind;
    cm_loc loc;
    char *var;             /* CMP, WITHIN, AGE, BOOLVAR */
    cm_loc var_loc;
    cm_cmp op;
    cm_aval value;         /* CMP, AGE, ELAPSED: compared value; WITHIN: the centre */
    cm_aval tol;           /* WITHIN: the tolerance; CMP: optional `tolerance` */
    bool has_tol;
    cm_aval hold;          /* `for T` */
    bool has_hold;
    char *handler;         /* CR_HANDLER */
    cm_aarg *args;
} cm_acrit;

typedef enum { E_AND, E_OR, E_NOT, E_TEST, E_DONE, E_FAILED, E_ELAPSED, E_TRUE, E_FALSE } cm_ekind;

typedef struct cm_aexpr {
    cm_ekind kind;
    cm_loc loc;
    struct cm_aexpr *a, *b;
    char *name;            /* E_TEST */
    cm_cmp op;             /* E_ELAPSED */
    cm_aval val;
} cm_aexpr;

typedef enum { HIST_NONE = 0, HIST_SHALLOW = 1, HIST_DEEP = 2 } cm_history;

typedef struct cm_atrans {
    struct cm_atrans *next;
    cm_loc loc;
    cm_aexpr *cond;
    char *text;            /* the condition as written */
    char *target;
    cm_loc target_loc;
    cm_history history;
} cm_atrans;

typedef enum { TM_ENTRY, TM_EXIT, TM_CYCLE, TM_EVERY, TM_AFTER } cm_time_model;

typedef struct cm_aaction {
    struct cm_aaction *next;
    cm_loc loc;
    bool is_set;           /* built-in `set VAR = VALUE` */
    char *behavior;        /* plugin behavior name */
    cm_loc beh_loc;
    cm_aarg *args;
    char *set_var;
    cm_loc set_var_loc;
    cm_aval set_val;
    cm_time_model tm;
    cm_aval period;        /* TM_EVERY, TM_AFTER */
} cm_aaction;

typedef struct cm_atest {
    struct cm_atest *next;
    cm_loc loc;
    char *name;
    cm_acrit crit;
} cm_atest;

typedef struct cm_astate {
    struct cm_astate *next;        /* sibling */
    struct cm_astate *children, *children_tail;
    cm_loc loc;
    char *name;
    char *start, *next_state;
    cm_loc start_loc, next_loc;
    bool next_is_done;
    cm_atest *tests, *tests_tail;
    cm_aaction *actions, *actions_tail;
    cm_atrans *trans, *trans_tail;
} cm_astate;

typedef struct cm_aparam {
    struct cm_aparam *next;
    cm_loc loc;
    char *name;
    cm_aval val;
    int depth;             /* include depth: the outermost file wins */
    bool is_override;      /* from -D (chasm_options.param_*) */
} cm_aparam;

typedef struct cm_ause {
    struct cm_ause *next;
    cm_loc loc;
    char *name;
} cm_ause;

typedef struct cm_avar {
    struct cm_avar *next;
    cm_loc loc;
    int kind;              /* chasm_var_kind */
    char *name;
    char *type_name;
    cm_loc type_loc;
    const cm_unit *unit;
    cm_aval init;
    bool has_init;
    cm_aval capacity;      /* `messages(N)` */
    cm_loc cap_loc;
    bool has_capacity;
} cm_avar;

typedef struct {
    char *mission_name;
    cm_aparam *params, *params_tail;
    cm_ause *uses, *uses_tail;
    cm_avar *vars, *vars_tail;
    cm_atest *tests, *tests_tail;          /* global tests */
    cm_atrans *aborts, *aborts_tail;
    cm_astate *roots, *roots_tail;
    char *start;
    cm_loc start_loc;
    int n_files;
    long n_lines;
} cm_aplan;
#endif
