/* The structural check of a plugin file (see cm_elf_check.h). It checks what
 * the dynamic linker reads before any code of the plugin runs: the ELF header,
 * the program header table, every segment's place in the file and in memory,
 * the dynamic section and the tables it points to. What it cannot see (a bad
 * relocation target symbol, code that crashes in a constructor) the probe
 * process of cm_plugin_file.c catches. Every read goes through get(), which
 * knows the buffer's length: this file is fuzzed (`make fuzz`). */
#include "chasm/cm_elf_check.h"

#include <elf.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* This build's ELF flavour: the only one dlopen can use. */
#if UINTPTR_MAX > 0xffffffffu
#define ELF_CLASS_HERE ELFCLASS64
typedef Elf64_Ehdr Ehdr;
typedef Elf64_Phdr Phdr;
typedef Elf64_Shdr Shdr;
typedef Elf64_Dyn Dyn;
#else
#define ELF_CLASS_HERE ELFCLASS32
typedef Elf32_Ehdr Ehdr;
typedef Elf32_Phdr Phdr;
typedef Elf32_Shdr Shdr;
typedef Elf32_Dyn Dyn;
#endif
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define ELF_DATA_HERE ELFDATA2LSB
#else
#define ELF_DATA_HERE ELFDATA2MSB
#endif
#if defined(__x86_64__)
#define ELF_MACHINE_HERE EM_X86_64
#define ELF_MACHINE_NAME "x86-64"
#elif defined(__aarch64__)
#define ELF_MACHINE_HERE EM_AARCH64
#define ELF_MACHINE_NAME "AArch64"
#elif defined(__i386__)
#define ELF_MACHINE_HERE EM_386
#define ELF_MACHINE_NAME "i386"
#elif defined(__arm__)
#define ELF_MACHINE_HERE EM_ARM
#define ELF_MACHINE_NAME "ARM"
#elif defined(__riscv)
#define ELF_MACHINE_HERE EM_RISCV
#define ELF_MACHINE_NAME "RISC-V"
#else
#define ELF_MACHINE_HERE 0 /* unknown here: dlopen checks the machine itself */
#define ELF_MACHINE_NAME "this machine"
#endif

#ifndef DT_RELR /* older elf.h */
#define DT_RELRSZ 35
#define DT_RELR 36
#endif

/* Most memory all segments of one plugin may ask for. */
#define MAX_IMAGE_BYTES (1024ull * 1024u * 1024u)

typedef struct {
    const unsigned char *data;
    size_t n;
    char *err;
    size_t el;
    Phdr load[CM_ELF_MAX_PHDRS];
    int n_load;
} elf_t;

static int fail(elf_t *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(elf_t *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (e->el) vsnprintf(e->err, e->el, fmt, ap);
    va_end(ap);
    return -1;
}

/* [off, off+len) lies in the file: no overflow, no read past the end. */
static int in_file(const elf_t *e, uint64_t off, uint64_t len) { return off <= e->n && len <= e->n - off; }

static void get(const elf_t *e, uint64_t off, void *out, size_t len) { memcpy(out, e->data + off, len); }

static int pow2_or_0(uint64_t a) { return (a & (a - 1)) == 0; }

/* The PT_LOAD holding memory [addr, addr+len), file-backed only if want_file. */
static const Phdr *load_of(const elf_t *e, uint64_t addr, uint64_t len, int want_file)
{
    for (int i = 0; i < e->n_load; i++) {
        const Phdr *p = &e->load[i];
        uint64_t size = want_file ? p->p_filesz : p->p_memsz;
        if (addr >= p->p_vaddr && addr - p->p_vaddr <= size && len <= size - (addr - p->p_vaddr)) return p;
    }
    return NULL;
}

static const char *type_name(uint32_t t)
{
    switch (t) {
    case PT_LOAD: return "LOAD";
    case PT_DYNAMIC: return "DYNAMIC";
    case PT_INTERP: return "INTERP";
    case PT_NOTE: return "NOTE";
    case PT_PHDR: return "PHDR";
    case PT_TLS: return "TLS";
    case PT_GNU_EH_FRAME: return "GNU_EH_FRAME";
    case PT_GNU_STACK: return "GNU_STACK";
    case PT_GNU_RELRO: return "GNU_RELRO";
    case PT_GNU_PROPERTY: return "GNU_PROPERTY";
    default: return "other";
    }
}

static int check_header(elf_t *e, Ehdr *h)
{
    if (e->n < 4 || memcmp(e->data, ELFMAG, SELFMAG))
        return fail(e, "not an ELF file (it does not begin with \\177ELF)");
    if (e->n < sizeof *h)
        return fail(e, "the file is %zu bytes, shorter than an ELF header (%zu bytes): truncated", e->n, sizeof *h);
    get(e, 0, h, sizeof *h);
    if (h->e_ident[EI_CLASS] != ELF_CLASS_HERE)
        return fail(e, "ELF class %u: this CHASM loads %d-bit plugins only", h->e_ident[EI_CLASS],
                    ELF_CLASS_HERE == ELFCLASS64 ? 64 : 32);
    if (h->e_ident[EI_DATA] != ELF_DATA_HERE)
        return fail(e, "ELF byte order %u is not this machine's", h->e_ident[EI_DATA]);
    if (h->e_ident[EI_VERSION] != EV_CURRENT || h->e_version != EV_CURRENT)
        return fail(e, "unknown ELF version %u", (unsigned)h->e_version);
    if (h->e_type != ET_DYN)
        return fail(e, "ELF type %u is not a shared object (%u): build the plugin with -shared", h->e_type, ET_DYN);
    if (ELF_MACHINE_HERE && h->e_machine != ELF_MACHINE_HERE)
        return fail(e, "built for ELF machine %u, this CHASM runs on %s (%u)", h->e_machine, ELF_MACHINE_NAME,
                    ELF_MACHINE_HERE);
    if (h->e_ehsize != sizeof *h || h->e_phentsize != sizeof(Phdr))
        return fail(e, "header sizes %u/%u are not those of this ELF class (%zu/%zu)", h->e_ehsize, h->e_phentsize,
                    sizeof *h, sizeof(Phdr));
    if (h->e_phnum == 0 || h->e_phnum > CM_ELF_MAX_PHDRS)
        return fail(e, "%u program headers (a plugin has 1 to %d)", h->e_phnum, CM_ELF_MAX_PHDRS);
    uint64_t table = (uint64_t)h->e_phnum * sizeof(Phdr);
    if (h->e_phoff % _Alignof(Phdr) || !in_file(e, h->e_phoff, table))
        return fail(e, "the program header table (offset %llu, %llu bytes) is not inside the file of %zu bytes: "
                       "truncated or corrupt",
                    (unsigned long long)h->e_phoff, (unsigned long long)table, e->n);
    return 0;
}

/* Checked last (the segments say more about a truncated file): the linker
 * does not read sections, but a file that lies about them is broken. */
static int check_sections(elf_t *e, const Ehdr *h)
{
    if (!h->e_shoff) return 0;
    if (h->e_shnum && h->e_shentsize != sizeof(Shdr))
        return fail(e, "section header size %u is not %zu", h->e_shentsize, sizeof(Shdr));
    uint64_t st = (uint64_t)(h->e_shnum ? h->e_shnum : 1) * sizeof(Shdr);
    if (!in_file(e, h->e_shoff, st))
        return fail(e, "the section header table (offset %llu, %llu bytes) ends past the end of the file (%zu bytes): "
                       "truncated", (unsigned long long)h->e_shoff, (unsigned long long)st, e->n);
    if (h->e_shnum && h->e_shstrndx != SHN_XINDEX && h->e_shstrndx >= h->e_shnum)
        return fail(e, "section name table index %u, but there are %u sections", h->e_shstrndx, h->e_shnum);
    return 0;
}

/* Loadable segments: inside the file, aligned, ascending, not overlapping. */
static int check_loads(elf_t *e, const Phdr *ph, int n)
{
    uint64_t end = 0;
    for (int i = 0; i < n; i++) {
        const Phdr *p = &ph[i];
        if (p->p_type != PT_LOAD) continue;
        if (p->p_filesz > p->p_memsz)
            return fail(e, "segment %d (LOAD) has more bytes in the file (%llu) than in memory (%llu)", i,
                        (unsigned long long)p->p_filesz, (unsigned long long)p->p_memsz);
        if (!in_file(e, p->p_offset, p->p_filesz))
            return fail(e, "segment %d (LOAD) needs file bytes %llu..%llu, but the file is %zu bytes: truncated", i,
                        (unsigned long long)p->p_offset, (unsigned long long)p->p_offset + p->p_filesz, e->n);
        if (!pow2_or_0(p->p_align) || (p->p_align > 1 && (p->p_vaddr - p->p_offset) % p->p_align))
            return fail(e, "segment %d (LOAD) has a bad alignment (%llu)", i, (unsigned long long)p->p_align);
        if (p->p_vaddr < end || p->p_memsz > MAX_IMAGE_BYTES || p->p_vaddr > MAX_IMAGE_BYTES ||
            p->p_vaddr + p->p_memsz > MAX_IMAGE_BYTES)
            return fail(e, "segment %d (LOAD) at address %llu, %llu bytes, overlaps another or is out of range", i,
                        (unsigned long long)p->p_vaddr, (unsigned long long)p->p_memsz);
        end = p->p_vaddr + p->p_memsz;
        e->load[e->n_load++] = *p;
    }
    if (!e->n_load) return fail(e, "no loadable segment");
    return 0;
}

/* Every other segment the linker reads in memory lies in a loaded one. */
static int check_others(elf_t *e, const Phdr *ph, int n, const Phdr **dyn)
{
    *dyn = NULL;
    for (int i = 0; i < n; i++) {
        const Phdr *p = &ph[i];
        if (p->p_type == PT_LOAD || p->p_type == PT_NULL || p->p_type == PT_GNU_STACK) continue;
        const char *t = type_name(p->p_type);
        if (!in_file(e, p->p_offset, p->p_filesz))
            return fail(e, "segment %d (%s) needs file bytes %llu..%llu, but the file is %zu bytes: truncated", i, t,
                        (unsigned long long)p->p_offset, (unsigned long long)p->p_offset + p->p_filesz, e->n);
        if (!pow2_or_0(p->p_align)) return fail(e, "segment %d (%s) has a bad alignment", i, t);
        if (p->p_type == PT_GNU_RELRO) {
            if (!load_of(e, p->p_vaddr, p->p_memsz, 0))
                return fail(e, "segment %d (GNU_RELRO) is not inside a loadable segment", i);
            continue;
        }
        if (p->p_type == PT_TLS && p->p_memsz > MAX_IMAGE_BYTES) return fail(e, "segment %d (TLS) is too big", i);
        if (p->p_filesz && !load_of(e, p->p_vaddr, p->p_filesz, 1))
            return fail(e, "segment %d (%s) is not inside the file part of a loadable segment", i, t);
        if (p->p_type == PT_DYNAMIC) {
            if (p->p_filesz < sizeof(Dyn)) return fail(e, "segment %d (DYNAMIC) is empty", i);
            if (*dyn) return fail(e, "two DYNAMIC segments");
            *dyn = p;
        }
    }
    if (!*dyn) return fail(e, "no DYNAMIC segment: not a shared object");
    return 0;
}

/* Where the bytes of memory address addr come from in the file. */
static uint64_t file_offset(const Phdr *load, uint64_t addr) { return load->p_offset + (addr - load->p_vaddr); }

enum { T_STRTAB, T_STRSZ, T_RELA, T_RELASZ, T_REL, T_RELSZ, T_JMPREL, T_PLTRELSZ, T_INIT_ARRAY, T_INIT_ARRAYSZ,
       T_FINI_ARRAY, T_FINI_ARRAYSZ, T_PREINIT, T_PREINITSZ, T_RELR, T_RELRSZ, T_N };

static int check_relocs(elf_t *e, uint64_t at, uint64_t size, size_t entsize, const char *what)
{
    const Phdr *l = load_of(e, at, size, 1);
    if (!l) return fail(e, "the %s table is not inside the file part of a loadable segment", what);
    if (size % entsize) return fail(e, "the %s table's size %llu is not a multiple of %zu", what, (unsigned long long)size, entsize);
    for (uint64_t k = 0; k < size / entsize; k++) {
        uint64_t r_offset; /* first field of Elf_Rel and Elf_Rela */
        Elf64_Addr a64;
        Elf32_Addr a32;
        if (sizeof(Dyn) == sizeof(Elf64_Dyn)) {
            get(e, file_offset(l, at) + k * entsize, &a64, sizeof a64);
            r_offset = a64;
        } else {
            get(e, file_offset(l, at) + k * entsize, &a32, sizeof a32);
            r_offset = a32;
        }
        if (!load_of(e, r_offset, sizeof(void *), 0))
            return fail(e, "%s relocation %llu writes to address %llu, outside the plugin's segments", what,
                        (unsigned long long)k, (unsigned long long)r_offset);
    }
    return 0;
}

/* The dynamic section: terminated, its tables inside the loaded image, its
 * names inside the string table, every relocation target inside the image. */
static int check_dynamic(elf_t *e, const Phdr *dp)
{
    const Phdr *l = load_of(e, dp->p_vaddr, dp->p_filesz, 1);
    uint64_t base = file_offset(l, dp->p_vaddr);
    size_t n = (size_t)(dp->p_filesz / sizeof(Dyn));
    uint64_t v[T_N];
    int have[T_N] = {0};
    static const int64_t tags[T_N] = {DT_STRTAB, DT_STRSZ, DT_RELA, DT_RELASZ, DT_REL, DT_RELSZ, DT_JMPREL, DT_PLTRELSZ,
                                      DT_INIT_ARRAY, DT_INIT_ARRAYSZ, DT_FINI_ARRAY, DT_FINI_ARRAYSZ, DT_PREINIT_ARRAY,
                                      DT_PREINIT_ARRAYSZ, DT_RELR, DT_RELRSZ};
    uint64_t pltrel = DT_RELA;
    int terminated = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        Dyn d;
        get(e, base + i * sizeof d, &d, sizeof d);
        if (d.d_tag == DT_NULL) {
            terminated = 1;
            break;
        }
        for (int k = 0; k < T_N; k++)
            if (d.d_tag == tags[k]) {
                v[k] = d.d_un.d_val;
                have[k] = 1;
            }
        switch (d.d_tag) {
        case DT_PLTREL: pltrel = d.d_un.d_val; break;
        case DT_RELAENT: if (d.d_un.d_val != sizeof(Elf64_Rela) && sizeof(Dyn) == sizeof(Elf64_Dyn)) return fail(e, "bad DT_RELAENT"); break;
        case DT_SYMENT: if (d.d_un.d_val != (sizeof(Dyn) == sizeof(Elf64_Dyn) ? sizeof(Elf64_Sym) : sizeof(Elf32_Sym))) return fail(e, "bad DT_SYMENT"); break;
        case DT_PLTGOT: case DT_HASH: case DT_GNU_HASH: case DT_SYMTAB: case DT_INIT: case DT_FINI:
        case DT_VERSYM: case DT_VERDEF: case DT_VERNEED:
            if (!load_of(e, d.d_un.d_ptr, 1, 0))
                return fail(e, "dynamic entry %zu (tag %lld) points to address %llu, outside the plugin's segments", i,
                            (long long)d.d_tag, (unsigned long long)d.d_un.d_ptr);
            break;
        default: break;
        }
    }
    if (!terminated) return fail(e, "the dynamic section has no end marker (DT_NULL)");
    if (!have[T_STRTAB] || !have[T_STRSZ]) return fail(e, "the dynamic section names no string table");
    const Phdr *sl = load_of(e, v[T_STRTAB], v[T_STRSZ], 1);
    if (!sl || v[T_STRSZ] == 0) return fail(e, "the string table is not inside the file part of a loadable segment");
    uint64_t str = file_offset(sl, v[T_STRTAB]);
    if (e->data[str + v[T_STRSZ] - 1]) return fail(e, "the string table does not end with a NUL");
    for (size_t k = 0; k < i; k++) { /* names: inside the string table */
        Dyn d;
        get(e, base + k * sizeof d, &d, sizeof d);
        if ((d.d_tag == DT_NEEDED || d.d_tag == DT_SONAME || d.d_tag == DT_RPATH || d.d_tag == DT_RUNPATH) &&
            d.d_un.d_val >= v[T_STRSZ])
            return fail(e, "dynamic entry %zu names string %llu, past the string table (%llu bytes)", k,
                        (unsigned long long)d.d_un.d_val, (unsigned long long)v[T_STRSZ]);
    }
    static const struct { int at, size; const char *what; } tables[] = {
        {T_INIT_ARRAY, T_INIT_ARRAYSZ, "init array"}, {T_FINI_ARRAY, T_FINI_ARRAYSZ, "fini array"},
        {T_PREINIT, T_PREINITSZ, "preinit array"}, {T_RELR, T_RELRSZ, "RELR relocation"}};
    for (size_t k = 0; k < sizeof tables / sizeof tables[0]; k++) {
        int a = tables[k].at, s = tables[k].size;
        if (have[a] != have[s] || (have[a] && !load_of(e, v[a], v[s], 0)))
            return fail(e, "the %s is not inside the plugin's segments", tables[k].what);
    }
    size_t rela = sizeof(Dyn) == sizeof(Elf64_Dyn) ? sizeof(Elf64_Rela) : sizeof(Elf32_Rela);
    size_t rel = sizeof(Dyn) == sizeof(Elf64_Dyn) ? sizeof(Elf64_Rel) : sizeof(Elf32_Rel);
    if (have[T_RELA] != have[T_RELASZ] || have[T_REL] != have[T_RELSZ] || have[T_JMPREL] != have[T_PLTRELSZ])
        return fail(e, "a relocation table without its size");
    if (have[T_RELA] && check_relocs(e, v[T_RELA], v[T_RELASZ], rela, "RELA")) return -1;
    if (have[T_REL] && check_relocs(e, v[T_REL], v[T_RELSZ], rel, "REL")) return -1;
    if (have[T_JMPREL]) {
        if (pltrel != DT_RELA && pltrel != DT_REL) return fail(e, "unknown PLT relocation type %llu", (unsigned long long)pltrel);
        if (check_relocs(e, v[T_JMPREL], v[T_PLTRELSZ], pltrel == DT_RELA ? rela : rel, "PLT")) return -1;
    }
    return 0;
}

int cm_elf_check(const unsigned char *data, size_t n, char *err, size_t errlen)
{
    elf_t e = {.data = data, .n = n, .err = err, .el = errlen};
    if (errlen) err[0] = 0;
    if (n > CM_PLUGIN_MAX_BYTES)
        return fail(&e, "the file is %zu bytes, more than the %u a plugin may have", n, CM_PLUGIN_MAX_BYTES);
    Ehdr h;
    if (check_header(&e, &h)) return -1;
    Phdr ph[CM_ELF_MAX_PHDRS];
    for (int i = 0; i < h.e_phnum; i++) get(&e, h.e_phoff + (uint64_t)i * sizeof(Phdr), &ph[i], sizeof(Phdr));
    const Phdr *dyn;
    if (check_loads(&e, ph, h.e_phnum) || check_others(&e, ph, h.e_phnum, &dyn) || check_dynamic(&e, dyn) ||
        check_sections(&e, &h))
        return -1;
    return 0;
}
