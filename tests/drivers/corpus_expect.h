/* The hostile corpora of the protocols' unit tests: every file of a folder
 * starts with a line "# expect: name=N name=N ...", the rest is the bytes.
 * corpus_check feeds each file's bytes to a fresh rig in reads of read_size,
 * then holds every named figure to its N ('_' in a name stands for a space:
 * "bad_crc=2" is the reason "bad crc"). */
#ifndef TESTS_DRIVERS_CORPUS_EXPECT_H
#define TESTS_DRIVERS_CORPUS_EXPECT_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    size_t read_size;
    void *(*open)(void);                                             /* a fresh rig, freed with free() */
    void (*read)(void *rig, const uint8_t *data, size_t n, size_t k); /* the k-th read (from 0) */
    void (*end)(void *rig, size_t reads);                            /* after the last read; may be NULL */
    long (*figure)(void *rig, const char *name);                     /* the figure a name stands for */
    const char *(*last_error)(void *rig);                            /* for the failure's message */
} corpus_rig;

/* Checks every file of dir (CHECKs of the unit harness); returns how many. */
int corpus_check(const char *dir, const corpus_rig *c);

#endif
