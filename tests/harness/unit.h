/* The one harness of the C and C++ unit-test programs (build/bin/
 * chasm_unit_tests, test_plugin_NAME, nav_unit_tests): tests are registered
 * by name, checks count failures and say file:line, and unit_main() runs
 *
 *   PROGRAM [--plugins DIR] [--list] [NAME]
 *
 * NAME alone, or every test; "ok NAME" or "FAIL NAME (N checks)" per test on
 * stdout, failed checks on stderr. Exit status 0 all passed, 1 a test
 * failed, 2 no test ran (NAME unknown). The pytest files run one test per
 * process, by name, in both builds (normal and ASan+UBSan).
 *
 * C and C++ alike: C lists its tests in arrays `{"name", fn},` ending in
 * {NULL, NULL} (the pytest files find names by that pattern); C++ writes
 * TEST(name) { ... }, registered before main by a static object. */
#ifndef UNIT_H
#define UNIT_H

#include <stdio.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const char *name;
    void (*fn)(void);
} unit_test;

extern int unit_failures;           /* failed checks so far, all tests */
extern const char *unit_plugin_dir; /* --plugins DIR ("." without it), for tests that load plugins */

/* Counts a failed check and prints "file:line: message" (no location when
 * file is NULL: a helper's own message, not where a test is). */
void unit_fail(const char *file, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
void unit_check_near(const char *file, int line, const char *expr, double a, double b, double tol);
void unit_check_str(const char *file, int line, const char *got, const char *expected);
void unit_check_has(const char *file, int line, const char *haystack, const char *needle);

/* Adds one test, or a list ending in {NULL, NULL}, in running order. */
void unit_register(const char *name, void (*fn)(void));
void unit_register_list(const unit_test *tests);
/* Runs what argv asks for; before_each (may be NULL) runs before each test.
 * Returns the exit status. */
int unit_main(int argc, char **argv, void (*before_each)(void));

#ifdef __cplusplus
}
#endif

#define UNIT_FAIL(...) unit_fail(__FILE__, __LINE__, __VA_ARGS__)
#define CHECK(cond)                                 \
    do {                                            \
        if (!(cond))                                \
            UNIT_FAIL("check failed: %s", #cond);   \
    } while (0)
/* |a - b| <= tol, printing both values when it fails. */
#define CHECK_NEAR(a, b, tol) unit_check_near(__FILE__, __LINE__, #a, (a), (b), (tol))
/* Equal strings (got may be NULL: it then fails as "(null)"). */
#define CHECK_STR(got, expected) unit_check_str(__FILE__, __LINE__, (got), (expected))
/* haystack (may be NULL) contains needle. */
#define CHECK_HAS(haystack, needle) unit_check_has(__FILE__, __LINE__, (haystack), (needle))

#ifdef __cplusplus
/* TEST(name) { ... }: a test registered by a static object, before main. */
struct unit_registrar {
    unit_registrar(const char *name, void (*fn)(void)) { unit_register(name, fn); }
};
#define TEST(name)                                          \
    static void name(void);                                 \
    static const unit_registrar unit_reg_##name(#name, name); \
    static void name(void)
#endif

#endif
