// operator new for nav_unit_tests, counted in unit_allocs like malloc & co.
// (tests/harness/unit_alloc.h): operator new lives in libstdc++, which the
// linker's --wrap does not reach, so every form of it is replaced here, and
// every delete frees what they return.
#include <cstddef>
#include <cstdlib>
#include <new>

#include "../../harness/unit_alloc.h"

static void *counted(size_t n, size_t align)
{
    unit_allocs++;
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
