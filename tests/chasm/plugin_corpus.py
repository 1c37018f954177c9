"""A hostile corpus of plugin files, generated from a good plugin: truncated at
many offsets, header fields corrupted, segments past the end of the file,
dynamic tables pointing outside the image, the wrong class or machine, text,
and the built test plugins that are valid ELF but refuse to load (a newer or
an older ABI, a schema with a hole, no symbol, a constructor that crashes,
exits or hangs). Each case carries a piece of the reason the loader must give.

Shared by the `chasm` tests (check -P, run --hotplug, describe) and the
manager upload tests."""

from __future__ import annotations

import os
import struct
from dataclasses import dataclass
from pathlib import Path

EHDR = struct.Struct("<16sHHIQQQIHHHHHH")
PHDR = struct.Struct("<IIQQQQQQ")
DYN = struct.Struct("<qQ")
PT_LOAD, PT_DYNAMIC = 1, 2
DT_NULL, DT_STRTAB, DT_RELA = 0, 5, 7


@dataclass
class Case:
    name: str
    data: bytes | None  # None: a special file made by make_special()
    reason: str  # a piece of the error text the loader must give


def _phdrs(elf: bytes) -> list[tuple[int, tuple]]:
    h = EHDR.unpack_from(elf)
    phoff, phnum = h[5], h[10]
    return [(phoff + i * PHDR.size, PHDR.unpack_from(elf, phoff + i * PHDR.size)) for i in range(phnum)]


def _set(elf: bytes, off: int, fmt: str, value: int) -> bytes:
    b = bytearray(elf)
    struct.pack_into(fmt, b, off, value)
    return bytes(b)


def _dynamic_entry(elf: bytes, tag: int) -> int | None:
    """File offset of the first dynamic entry with that tag."""
    for _, p in _phdrs(elf):
        if p[0] == PT_DYNAMIC:
            for k in range(p[5] // DYN.size):
                off = p[2] + k * DYN.size
                t, _v = DYN.unpack_from(elf, off)
                if t == tag:
                    return off
                if t == DT_NULL:
                    return None
    return None


def byte_cases(good: bytes) -> list[Case]:
    """Every hostile file that is plain bytes (uploadable)."""
    cases: list[Case] = []
    ph = _phdrs(good)
    loads = [p for _, p in ph if p[0] == PT_LOAD]
    cuts = {0, 1, 3, 4, 16, 40, 63, 64, 100, len(good) // 4, len(good) // 2, len(good) * 3 // 4, len(good) - 1}
    cuts |= {EHDR.unpack_from(good)[5] + len(ph) * PHDR.size - 1}
    for p in loads:  # just inside the end of each loadable segment's file bytes
        end = p[2] + p[5]
        if 0 < end - 8 < len(good):
            cuts.add(end - 8)
    for cut in sorted(cuts):
        reason = "empty" if cut == 0 else "not an ELF file" if cut < 4 else "truncated"
        cases.append(Case(f"truncated_at_{cut}", good[:cut], reason))
    cases += [
        Case("text_file", b"this is not a plugin, it is a text file\n" * 20, "not an ELF file"),
        Case("elf_magic_only", b"\x7fELF garbage", "truncated"),
        Case("wrong_class", _set(good, 4, "<B", 1), "64-bit plugins only"),
        Case("wrong_byte_order", _set(good, 5, "<B", 2), "byte order"),
        Case("executable_type", _set(good, 16, "<H", 2), "not a shared object"),
        Case("relocatable_type", _set(good, 16, "<H", 1), "not a shared object"),
        Case("wrong_machine", _set(good, 18, "<H", 183), "machine 183"),
        Case("bad_phentsize", _set(good, 54, "<H", 0), "header sizes"),
        Case("no_phdrs", _set(good, 56, "<H", 0), "program headers"),
        Case("many_phdrs", _set(good, 56, "<H", 0xFFFF), "program headers"),
        Case("phoff_past_end", _set(good, 32, "<Q", len(good) + 4096), "program header table"),
        Case("phoff_huge", _set(good, 32, "<Q", 2**64 - 64), "program header table"),
        Case("shoff_past_end", _set(good, 40, "<Q", len(good) + 1), "section header table"),
        Case("bad_shstrndx", _set(good, 62, "<H", 0xFFF0), "section name table"),
    ]
    first_load = next(off for off, p in ph if p[0] == PT_LOAD)
    last_load = [off for off, p in ph if p[0] == PT_LOAD][-1]
    off = PHDR.unpack_from(good, last_load)[2]
    beyond = _set(
        _set(good, last_load + 32, "<Q", len(good) - off + 4096), last_load + 40, "<Q", len(good) - off + 8192
    )
    cases += [
        Case("segment_beyond_eof", beyond, "truncated"),
        Case("segment_offset_huge", _set(good, last_load + 8, "<Q", 2**63), "truncated"),
        Case("segment_memsz_small", _set(good, first_load + 40, "<Q", 1), "more bytes in the file"),
        Case("segment_bad_align", _set(good, first_load + 48, "<Q", 3), "alignment"),
    ]
    dyn = next(off for off, p in ph if p[0] == PT_DYNAMIC)
    cases += [
        Case("dynamic_outside", _set(good, dyn + 16, "<Q", 2**40), "not inside"),
        Case("dynamic_offset_past_end", _set(good, dyn + 8, "<Q", len(good)), "truncated"),
    ]
    strtab = _dynamic_entry(good, DT_STRTAB)
    if strtab is not None:
        cases.append(Case("strtab_outside", _set(good, strtab + 8, "<Q", 2**33), "string table"))
    rela = _dynamic_entry(good, DT_RELA)
    if rela is not None:
        cases.append(Case("relocations_outside", _set(good, rela + 8, "<Q", 2**33), "RELA"))
    return cases


SPECIAL = ["directory", "symlink_loop", "dangling_symlink", "fifo"]


def make_special(kind: str, path: Path) -> str:
    """Makes a non-file at path; returns a piece of the expected reason."""
    if kind == "directory":
        path.mkdir()
        return "directory"
    if kind == "symlink_loop":
        os.symlink(path.name, path)
        return "symbolic links"
    if kind == "dangling_symlink":
        os.symlink(path.parent / "no-such-target.so", path)
        return "No such file"
    if kind == "fifo":
        os.mkfifo(path)
        return "not a regular file"
    raise ValueError(kind)


# Built test plugins (tests/chasm/plugins/) that are ELF files that load badly.
BUILT = [
    ("test_basic_badabi", "plugin ABI"),
    ("test_basic_abi2", "built for plugin ABI 2, this CHASM uses ABI 3"),
    ("test_hole", "behavior 'holey': parameter slot 1 of 3 is empty"),
    ("test_nosym", "does not export"),
    ("test_ctor_crash", "crashed the probe process"),
    ("test_ctor_exit", "ended the probe process"),
]
# Costs the probe's time limit (2 s) per load: used once per build variant.
HANG = ("test_ctor_hang", "did not finish loading")


def built_cases(plugins: Path) -> list[Case]:
    return [Case(name, (plugins / f"chasm_{name}.so").read_bytes(), reason) for name, reason in BUILT]
