/* The unit-test harness (unit.h): registry, checks, and the runner. */
#include "unit.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>

/* More than all three programs have (about 90 at most); a fixed table, so
 * registering allocates nothing the allocation-counting tests could see. */
#define UNIT_MAX_TESTS 1024

int unit_failures;
const char *unit_plugin_dir = ".";

static unit_test registry[UNIT_MAX_TESTS];
static size_t n_registered;

void unit_fail(const char *file, int line, const char *fmt, ...)
{
    if (file)
        fprintf(stderr, "%s:%d: ", file, line);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    unit_failures++;
}

void unit_check_near(const char *file, int line, const char *expr, double a, double b, double tol)
{
    if (!(fabs(a - b) <= tol))
        unit_fail(file, line, "%s = %.9g, expected %.9g +- %g", expr, a, b, tol);
}

void unit_check_str(const char *file, int line, const char *got, const char *expected)
{
    if (!got || strcmp(got, expected))
        unit_fail(file, line, "expected \"%s\", got \"%s\"", expected, got ? got : "(null)");
}

void unit_check_has(const char *file, int line, const char *haystack, const char *needle)
{
    if (!haystack || !strstr(haystack, needle))
        unit_fail(file, line, "\"%s\" does not contain \"%s\"", haystack ? haystack : "(null)", needle);
}

void unit_register(const char *name, void (*fn)(void))
{
    if (n_registered == UNIT_MAX_TESTS) { /* a build problem, not a test failure */
        fprintf(stderr, "unit.c: more than %d tests: raise UNIT_MAX_TESTS\n", UNIT_MAX_TESTS);
        exit(2);
    }
    registry[n_registered++] = (unit_test){name, fn};
}

void unit_register_list(const unit_test *tests)
{
    for (; tests->name; tests++)
        unit_register(tests->name, tests->fn);
}

/* --plugins DIR, --list, NAME; the name asked for, NULL for every test. */
static const char *parse_args(int argc, char **argv, int *list)
{
    const char *only = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--plugins") && i + 1 < argc)
            unit_plugin_dir = argv[++i];
        else if (!strcmp(argv[i], "--list"))
            *list = 1;
        else
            only = argv[i];
    }
    return only;
}

/* Runs one test; 1 when it passed. */
static int run_one(const unit_test *t, void (*before_each)(void))
{
    if (before_each)
        before_each();
    const int before = unit_failures;
    t->fn();
    if (unit_failures == before) {
        printf("ok %s\n", t->name);
        return 1;
    }
    printf("FAIL %s (%d checks)\n", t->name, unit_failures - before);
    return 0;
}

int unit_main(int argc, char **argv, void (*before_each)(void))
{
    int list = 0;
    const char *only = parse_args(argc, argv, &list);
    int ran = 0, failed = 0;
    for (size_t i = 0; i < n_registered; i++) {
        if (list)
            printf("%s\n", registry[i].name);
        else if (!only || !strcmp(only, registry[i].name)) {
            ran++;
            failed += !run_one(&registry[i], before_each);
        }
    }
    if (list)
        return 0;
    if (!ran) {
        fprintf(stderr, "no test named '%s'\n", only ? only : "");
        return 2;
    }
    return failed ? 1 : 0;
}
