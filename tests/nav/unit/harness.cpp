#include "harness.hpp"

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

int g_failures = 0;
long g_allocs = 0;

extern "C" {
void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t k);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t k);
void *__wrap_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n) { g_allocs++; return __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t k) { g_allocs++; return __real_calloc(n, k); }
void *__wrap_realloc(void *p, size_t n) { g_allocs++; return __real_realloc(p, n); }
}

// operator new lives in libstdc++ (not wrapped by the linker): every form of
// it is replaced here and counted, and every delete frees what they return.
static void *counted(size_t n, size_t align)
{
    g_allocs++;
    if (align <= alignof(std::max_align_t))
        return __real_malloc(n ? n : 1);
    return std::aligned_alloc(align, (n + align - 1) / align * align);
}
void *operator new(size_t n)
{
    if (void *p = counted(n, 0))
        return p;
    throw std::bad_alloc();
}
void *operator new[](size_t n) { return operator new(n); }
void *operator new(size_t n, const std::nothrow_t &) noexcept { return counted(n, 0); }
void *operator new[](size_t n, const std::nothrow_t &) noexcept { return counted(n, 0); }
void *operator new(size_t n, std::align_val_t a)
{
    if (void *p = counted(n, static_cast<size_t>(a)))
        return p;
    throw std::bad_alloc();
}
void *operator new[](size_t n, std::align_val_t a) { return operator new(n, a); }
void operator delete(void *p) noexcept { std::free(p); }
void operator delete[](void *p) noexcept { std::free(p); }
void operator delete(void *p, size_t) noexcept { std::free(p); }
void operator delete[](void *p, size_t) noexcept { std::free(p); }
void operator delete(void *p, const std::nothrow_t &) noexcept { std::free(p); }
void operator delete[](void *p, const std::nothrow_t &) noexcept { std::free(p); }
void operator delete(void *p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void *p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void *p, size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void *p, size_t, std::align_val_t) noexcept { std::free(p); }

static std::vector<UnitTest *> &registry()
{
    static std::vector<UnitTest *> r;
    return r;
}

UnitTest::UnitTest(const char *n, void (*f)()) : name(n), fn(f) { registry().push_back(this); }

int main(int argc, char **argv)
{
    int ran = 0;
    for (UnitTest *t : registry()) {
        if (argc > 1 && std::strcmp(argv[1], t->name) != 0)
            continue;
        const int before = g_failures;
        t->fn();
        ran++;
        if (g_failures == before)
            std::printf("ok %s\n", t->name);
        else
            std::printf("FAILED %s\n", t->name);
    }
    if (argc > 1 && !ran) {
        std::fprintf(stderr, "no test named %s\n", argv[1]);
        return 2;
    }
    if (argc == 1 && std::getenv("NAV_UNIT_LIST")) {
        for (UnitTest *t : registry())
            std::printf("%s\n", t->name);
    }
    return g_failures ? 1 : 0;
}
