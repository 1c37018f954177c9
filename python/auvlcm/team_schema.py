"""The team-link schema (c/plugins/team/team_link.schema): parsed and checked.

One parser for both readers of the schema: the C generator
(python/tools/codegen/gen_team_codec.py) and the run-time Python codec
(auvlcm.team_codec). Every fault is reported at once, each as
`file:line:col: message`, so the two can never disagree on what a schema means.

Bits: a field takes ceil(log2((MAX - MIN) / STEP + 1)) bits; a message is a
4-bit id then its fields, most significant bit first.
"""

from __future__ import annotations

import keyword
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

ID_BITS = 4
MAX_ID = (1 << ID_BITS) - 1
MAX_FIELD_BITS = 32
# (MAX - MIN) / STEP within this (relative) of a whole number counts as whole:
# 102.3 / 0.1 is 1022.9999999999999 in binary floating point.
WHOLE_TOLERANCE = 1e-9

DEFAULT_SCHEMA = Path(__file__).resolve().parents[2] / "c" / "plugins" / "team" / "team_link.schema"

NAME_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
# C keywords (C11) and names that would clash with what the generator writes.
C_KEYWORDS = frozenset(
    """auto break case char const continue default do double else enum
extern float for goto if inline int long register restrict return short signed sizeof
static struct switch typedef union unsigned void volatile while _Alignas _Alignof _Atomic
_Bool _Complex _Generic _Imaginary _Noreturn _Static_assert _Thread_local""".split()
)
RESERVED_FIELDS = frozenset({"id"})


class SchemaError(Exception):
    """Every fault of one schema, each line `file:line:col: message`."""

    def __init__(self, errors: list[str]):
        super().__init__("\n".join(errors))
        self.errors = errors


@dataclass(frozen=True)
class Field:
    name: str
    kind: str  # "int" or "fixed"
    lo: float
    hi: float
    step: float
    steps: int  # raw values run 0..steps
    bits: int
    line: int
    comment: str = ""

    @property
    def is_int(self) -> bool:
        return self.kind == "int"


@dataclass
class Message:
    name: str
    id: int
    max_bytes: int
    line: int
    col: int
    fields: list[Field] = field(default_factory=list)
    faulty: bool = False  # a field line was refused: no size or emptiness check

    @property
    def bits(self) -> int:
        """Bits of one encoded message, its id included."""
        return ID_BITS + sum(f.bits for f in self.fields)

    @property
    def nbytes(self) -> int:
        """Bytes of a frame holding this message alone."""
        return (self.bits + 7) // 8


@dataclass
class Schema:
    path: str
    messages: list[Message]

    def by_name(self, name: str) -> Message:
        for m in self.messages:
            if m.name == name:
                return m
        raise KeyError(f"team schema has no message {name!r} (known: {', '.join(m.name for m in self.messages)})")

    def by_id(self, ident: int) -> Message | None:
        for m in self.messages:
            if m.id == ident:
                return m
        return None


def _tokens(line: str) -> list[tuple[str, int]]:
    """Words of one line before any '#', each with its 1-based column."""
    code = line.split("#", 1)[0]
    return [(m.group(0), m.start() + 1) for m in re.finditer(r"\S+", code)]


def _number(text: str) -> float | None:
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def _whole(x: float) -> int | None:
    """x as an int when it is (within rounding) a whole number."""
    n = round(x)
    return n if abs(x - n) <= WHOLE_TOLERANCE * max(1.0, abs(x)) else None


def _bad_name(name: str) -> str | None:
    if not NAME_RE.match(name):
        return f"'{name}' is not a name (letters, digits and '_', not starting with a digit)"
    if name in C_KEYWORDS or keyword.iskeyword(name):
        return f"'{name}' is a keyword of C or Python: choose another name"
    return None


def parse_text(text: str, path: str = "<schema>") -> Schema:
    errors: list[str] = []
    messages: list[Message] = []
    current: Message | None = None

    def err(line: int, col: int, msg: str) -> None:
        errors.append(f"{path}:{line}:{col}: {msg}")

    for lineno, line in enumerate(text.splitlines(), start=1):
        toks = _tokens(line)
        if not toks:
            continue
        word, col = toks[0]
        if word == "message":
            current = _parse_message(toks, lineno, err, messages)
            if current is not None and not isinstance(current, _Orphan):
                messages.append(current)
            continue
        if current is None:
            err(lineno, col, f"'{word}': a field needs a 'message NAME ID max_bytes N' line above it")
            continue
        f = _parse_field(toks, lineno, err, current, line.partition("#")[2].strip())
        if f is not None:
            current.fields.append(f)
        else:
            current.faulty = True
    for m in messages:
        if m.faulty:
            continue
        if not m.fields:
            err(m.line, m.col, f"message '{m.name}' has no fields")
        elif m.nbytes > m.max_bytes:
            err(
                m.line,
                m.col,
                f"message '{m.name}' takes {m.bits} bits = {m.nbytes} bytes, "
                f"over its max_bytes {m.max_bytes}: widen a step or narrow a range",
            )
    if not messages and not errors:
        err(1, 1, "the schema declares no message")
    if errors:
        raise SchemaError(errors)
    return Schema(path, messages)


def _parse_message(toks, lineno, err, messages: list[Message]) -> Message:
    col0 = toks[0][1]
    if len(toks) != 5 or toks[3][0] != "max_bytes":
        err(lineno, col0, "expected 'message NAME ID max_bytes N'")
        return _Orphan("?", -1, 0, lineno, col0)
    (name, ncol), (ident_text, icol), _, (nb_text, bcol) = toks[1:]
    ok = True
    bad = _bad_name(name)
    if bad:
        err(lineno, ncol, bad)
        ok = False
    elif any(m.name == name for m in messages):
        first = next(m for m in messages if m.name == name)
        err(lineno, ncol, f"message '{name}' is declared twice (first on line {first.line})")
        ok = False
    ident = int(ident_text) if re.fullmatch(r"\d+", ident_text) else -1
    if not 1 <= ident <= MAX_ID:
        err(lineno, icol, f"message id '{ident_text}' must be a whole number 1..{MAX_ID} (0 ends a frame)")
        ok = False
    else:
        for m in messages:
            if m.id == ident:
                err(lineno, icol, f"message id {ident} repeats message '{m.name}' (line {m.line})")
                ok = False
    nbytes = int(nb_text) if re.fullmatch(r"\d+", nb_text) else 0
    if nbytes < 1:
        err(lineno, bcol, f"max_bytes '{nb_text}' must be a whole number >= 1")
        ok = False
    # A faulty header still collects its fields (their faults are reported
    # too), in a message that is then dropped.
    m = Message(name, ident, nbytes, lineno, ncol)
    return m if ok else _Orphan(name, ident, nbytes, lineno, ncol)


class _Orphan(Message):
    """Fields of a message whose header line was refused: still checked."""


def _parse_field(toks, lineno, err, msg: Message, comment: str) -> Field | None:
    name, ncol = toks[0]
    if len(toks) < 2 or toks[1][0] not in ("int", "fixed"):
        col = toks[1][1] if len(toks) > 1 else ncol
        err(lineno, col, f"field '{name}': expected 'int MIN MAX' or 'fixed MIN MAX STEP'")
        return None
    kind, kcol = toks[1]
    want = 4 if kind == "int" else 5
    if len(toks) != want:
        col = toks[want][1] if len(toks) > want else toks[-1][1]
        err(lineno, col, f"field '{name}': expected " + ("'int MIN MAX'" if kind == "int" else "'fixed MIN MAX STEP'"))
        return None
    ok = True
    bad = _bad_name(name)
    if bad:
        err(lineno, ncol, bad)
        ok = False
    elif name in RESERVED_FIELDS:
        err(lineno, ncol, f"field name '{name}' is reserved")
        ok = False
    elif any(f.name == name for f in msg.fields):
        err(lineno, ncol, f"field '{name}' repeats in message '{msg.name}'")
        ok = False
    values = []
    for text, col in toks[2:]:
        v = _number(text)
        if v is None:
            err(lineno, col, f"'{text}' is not a number")
            ok = False
        elif kind == "int" and (_whole(v) is None or not -(2**31) <= v <= 2**31 - 1):
            err(lineno, col, f"'{text}': an int field's bounds are whole numbers of 32 bits")
            ok = False
        values.append(v)
    if not ok:
        return None
    lo, hi = values[0], values[1]
    step = values[2] if kind == "fixed" else 1.0
    if hi <= lo:
        err(lineno, toks[3][1], f"field '{name}': MAX {toks[3][0]} must be above MIN {toks[2][0]}")
        return None
    if step <= 0:
        err(lineno, toks[4][1], f"field '{name}': STEP {toks[4][0]} must be above 0")
        return None
    steps = _whole((hi - lo) / step)
    if steps is None:
        err(
            lineno,
            toks[4][1],
            f"field '{name}': MAX - MIN ({hi - lo:g}) is not a whole number of steps of {step:g}: adjust MAX or STEP",
        )
        return None
    bits = max(1, steps.bit_length())
    if bits > MAX_FIELD_BITS:
        err(lineno, toks[2][1], f"field '{name}' would take {bits} bits (at most {MAX_FIELD_BITS})")
        return None
    return Field(name, kind, lo, hi, step, steps, bits, lineno, comment)


def load(path: str | Path = DEFAULT_SCHEMA) -> Schema:
    """Parse a schema file; SchemaError lists every fault."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as e:
        raise SchemaError([f"{p}:1:1: cannot read the schema: {e}"]) from None
    return parse_text(text, str(path))
