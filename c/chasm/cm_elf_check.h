/* The structural check of a plugin file, before anything maps it.
 *
 * dlopen trusts the file: a segment that reaches past the end of a truncated
 * file is mapped anyway and the first touch of it is a SIGBUS inside the
 * dynamic linker; a header field out of range sends it to read anywhere. This
 * check runs on the bytes in memory (no I/O, no allocation, so it can be fuzzed)
 * and refuses, with a reason, any file whose headers do not describe a shared
 * object of this build's class, byte order and machine lying inside the file. */
#ifndef CM_ELF_CHECK_H
#define CM_ELF_CHECK_H
#include <stddef.h>

/* Largest plugin file accepted, in bytes (our plugins are 20-200 KB). */
#define CM_PLUGIN_MAX_BYTES (64u * 1024u * 1024u)
/* Most program headers accepted (a linker writes about ten). */
#define CM_ELF_MAX_PHDRS 64

/* 0 when data[0..n) is a loadable shared object for this build; else -1 and
 * the reason in err ("the file is 812 bytes, its segment 2 ends at 14224"). */
int cm_elf_check(const unsigned char *data, size_t n, char *err, size_t errlen);
#endif
