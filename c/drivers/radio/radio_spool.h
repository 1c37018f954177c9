/* The spool's files (radio_asm.h gives their format): written and read here,
 * in the Python reference's JSON, so that either gateway resumes what the
 * other held. Only the few keys of that format are read; anything else in a
 * file makes it unreadable (then the transfer is dropped, as the Python's). */
#ifndef RADIO_SPOOL_H
#define RADIO_SPOOL_H

#include <stddef.h>
#include <stdint.h>

#include "drivers/radio/radio_asm.h"

void rsp_path(const ra_assembler *a, int64_t tid, const char *ext, char *out, size_t cap);
/* <id>.json for p, through a temporary file and a rename. 0 or -1. */
int rsp_save_meta(const ra_assembler *a, const ra_partial *p);
/* done.json. 0 or -1. */
int rsp_save_done(const ra_assembler *a);
/* Reads a <id>.json; 0, or -1 when it is not one the format allows. */
int rsp_load_meta(const char *path, ra_partial *p);
/* Reads done.json's ids, the last `cap` of them; their number, or -1. */
int rsp_load_done(const char *path, int64_t *ids, int cap);

#endif
