/* Binding files that include other binding files (mgr_bind_files.c): the
 * chain of files being read, so a cycle is refused where it closes and an
 * error in an included file names that file. Internal to the parser. */
#ifndef MGR_BIND_FILES_H
#define MGR_BIND_FILES_H

#include <stddef.h>

#include "managers/mgr_bindings.h"

typedef struct mgr_bind_chain {
    const char *path;                 /* as named: what messages print */
    const char *real;                 /* realpath(), NULL if unknown (text with no file) */
    const struct mgr_bind_chain *up;  /* the file that included this one; NULL at the top */
    int depth;                        /* 0 at the top */
} mgr_bind_chain;

/* Parse text as the file `chain->path` (mgr_bind_parse.c). */
int mgr_bind_parse_chain(mgr_bindings *b, const mgr_bind_chain *chain, const char *text, size_t len,
                         const char *vehicle, mgr_errors *errs);
/* Read and parse the file `name` that line `lineno` (the name at `col`) of
 * chain->path includes, resolved relative to chain->path's folder. */
int mgr_bind_include(mgr_bindings *b, const mgr_bind_chain *chain, int lineno, int col, const char *name,
                     const char *vehicle, mgr_errors *errs);

#endif
