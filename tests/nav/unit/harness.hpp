// Tiny harness for the filter's C++ unit tests: `nav_unit_tests NAME` runs
// one test, no argument runs all; "ok NAME" per passing test. Allocations are
// counted (operator new and malloc & co., wrapped at link time) so a test can
// prove that a filter update allocates nothing.
#ifndef NAV_UNIT_HARNESS_HPP
#define NAV_UNIT_HARNESS_HPP

#include <cmath>
#include <cstdio>
#include <string>

extern int g_failures;
extern long g_allocs;

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            g_failures++;                                                            \
        }                                                                            \
    } while (0)
#define CHECK_NEAR(a, b, tol)                                                                        \
    do {                                                                                             \
        const double a_ = (a), b_ = (b);                                                             \
        if (!(std::fabs(a_ - b_) <= (tol))) {                                                        \
            std::fprintf(stderr, "%s:%d: %s = %.9g, expected %.9g +- %g\n", __FILE__, __LINE__, #a, a_, b_, \
                         static_cast<double>(tol));                                                  \
            g_failures++;                                                                            \
        }                                                                                            \
    } while (0)
#define CHECK_EQ_STR(a, b)                                                                                    \
    do {                                                                                                      \
        const std::string a_ = (a), b_ = (b);                                                                 \
        if (a_ != b_) {                                                                                       \
            std::fprintf(stderr, "%s:%d: got\n  \"%s\"\nexpected\n  \"%s\"\n", __FILE__, __LINE__, a_.c_str(), b_.c_str()); \
            g_failures++;                                                                                     \
        }                                                                                                     \
    } while (0)

struct UnitTest {
    const char *name;
    void (*fn)();
    UnitTest(const char *n, void (*f)());
};
#define TEST(name)                              \
    static void name();                         \
    static UnitTest reg_##name(#name, name);    \
    static void name()

#endif
