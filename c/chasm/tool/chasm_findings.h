/* `chasm check`'s deeper checks (chasm_lint): findings printed as
 * "file:line:col: warning: [kind] message" on stdout. */
#ifndef CHASM_FINDINGS_H
#define CHASM_FINDINGS_H
#include "chasm/chasm.h"

/* The findings not marked expected in the plan; a finding is expected when the
 * line it points at, or the line above, holds "chasm-check: expected" (a
 * comment saying why). */
int chasm_check_deeper(const chasm_machine *m);
#endif
