"""SymPy printers and line wrapping for the generated Fortran.

The printers subclass SymPy's ``FCodePrinter`` only to print numbers the project's way (``_wp``
kind suffixes in the module, ``D0`` exponents in ``ucosub.f``) and to leave line wrapping to
this module, which never breaks inside a name, a number or a string.
"""

from __future__ import annotations

import re

import sympy
from sympy.printing.fortran import FCodePrinter
from sympy.printing.precedence import precedence

__all__ = [
    "FREE_WIDTH",
    "FIXED_WIDTH",
    "ModulePrinter",
    "LegacyPrinter",
    "wrap_free",
    "wrap_fixed",
    "wrap_comment",
    "free_string",
    "fixed_string",
]

#: Preferred and hard line lengths of the free-form module (the project's Fortran style: 100, and
#: gfortran's free-form limit of 132).
FREE_WIDTH = 100
#: Last column of a fixed-form statement.
FIXED_WIDTH = 72


class ModulePrinter(FCodePrinter):
    """Free-form Fortran 2008 expressions whose real literals carry the kind ``wp``.

    Integers print as real literals (``2.0_wp*x``) except integer exponents, which stay
    integers so ``x**2`` is a multiplication; rationals print as a quotient of real literals;
    pi and other number symbols as a literal with every digit a double holds.
    """

    def __init__(self) -> None:
        super().__init__({"source_format": "free", "standard": 2008, "name_mangling": False,
                          "precision": 17, "strict": True})

    def real_literal(self, value: float) -> str:
        """Shortest text that reads back as ``value``, with the kind suffix."""
        mantissa, exponent = self._split_float(value)
        return f"{mantissa}e{exponent}_wp" if exponent else f"{mantissa}_wp"

    @staticmethod
    def _split_float(value: float) -> tuple[str, int]:
        """Mantissa with a decimal point and the decimal exponent of Python's repr."""
        text = repr(float(value))
        if text in ("inf", "-inf", "nan"):
            raise ValueError(f"cannot print the non-finite number {text}")
        mantissa, _, exponent = text.partition("e")
        if "." not in mantissa:
            mantissa += ".0"
        return mantissa, int(exponent or 0)

    def expression(self, expr: sympy.Expr) -> str:
        """The Fortran text of one expression, unwrapped."""
        self._not_supported: set[sympy.Basic] = set()
        self._number_symbols: set[tuple[sympy.Basic, sympy.Float]] = set()
        return str(self._print(expr))

    def _print_Float(self, expr: sympy.Float) -> str:
        return self.real_literal(float(expr))

    def _print_Integer(self, expr: sympy.Integer) -> str:
        return self.real_literal(float(int(expr)))

    def _print_Rational(self, expr: sympy.Rational) -> str:
        return (f"{self.real_literal(float(int(expr.p)))}/"
                f"{self.real_literal(float(int(expr.q)))}")

    def _print_NumberSymbol(self, expr: sympy.NumberSymbol) -> str:
        return self.real_literal(float(expr.evalf(20)))

    def _print_Pow(self, expr: sympy.Pow) -> str:
        prec = precedence(expr)
        base, exponent = expr.base, expr.exp
        if exponent == -1:
            return f"{self.real_literal(1.0)}/{self.parenthesize(base, prec)}"
        if exponent == sympy.S.Half:
            return f"sqrt({self._print(base)})"
        if exponent == -sympy.S.Half:
            return f"{self.real_literal(1.0)}/sqrt({self._print(base)})"
        if exponent.is_Integer:
            power = int(exponent)
            text = str(power) if power >= 0 else f"({power})"
            return f"{self.parenthesize(base, prec, strict=True)}**{text}"
        return (f"{self.parenthesize(base, prec, strict=True)}"
                f"**{self.parenthesize(exponent, prec, strict=True)}")


class LegacyPrinter(ModulePrinter):
    """Fixed-form FORTRAN 77 expressions: DOUBLE PRECISION literals with a ``D`` exponent."""

    def __init__(self) -> None:
        FCodePrinter.__init__(self, {"source_format": "fixed", "standard": 77,
                                     "name_mangling": False, "precision": 17, "strict": True})

    def real_literal(self, value: float) -> str:
        """Shortest text that reads back as ``value``, as a DOUBLE PRECISION constant."""
        mantissa, exponent = self._split_float(value)
        return f"{mantissa}D{exponent}"

    def expression(self, expr: sympy.Expr) -> str:
        """The FORTRAN 77 text of one expression, in upper case, unwrapped."""
        return super().expression(expr).upper()


# --- line wrapping --------------------------------------------------------------------------


_OPERATORS = ("// ", "+ ", "- ", ".and. ", ".or. ", ".AND. ", ".OR. ")


def _break_points(text: str) -> list[tuple[int, int]]:
    """Positions where a statement may be split, with a priority (lower is better): a blank
    before a binary operator (0), any other blank (1), after ``(``, a single ``*`` or a single
    ``/`` (2). Never inside a string literal."""
    points = []
    quote = ""
    for i, char in enumerate(text):
        if quote:
            if char == quote:
                quote = ""
            continue
        if char in "'\"":
            quote = char
        elif char == " ":
            points.append((i, 0 if text.startswith(_OPERATORS, i + 1) else 1))
        elif char == "(" or (char in "*/" and text[i - 1:i] != char
                             and text[i + 1:i + 2] != char):
            points.append((i + 1, 2))
    return points


def _split(text: str, first: int, rest: int) -> list[str]:
    """Split ``text`` into pieces of at most ``first`` then ``rest`` characters, each cut at
    the best break point in the last 40 % of the room, or at the last one that fits."""
    pieces = []
    width = first
    while len(text) > width:
        points = [(p, priority) for p, priority in _break_points(text) if 0 < p <= width]
        if not points:
            raise ValueError(f"cannot wrap: {text[:60]}...")
        window = [(priority, -p) for p, priority in points if p > 0.6 * width]
        cut = -min(window)[1] if window else points[-1][0]
        pieces.append(text[:cut].rstrip())
        text = text[cut:].lstrip()
        width = rest
    pieces.append(text)
    return pieces


def wrap_free(statement: str, indent: int, width: int = FREE_WIDTH) -> list[str]:
    """A free-form statement as lines of at most ``width``: ``&`` ends a continued line and
    starts the next, four columns deeper."""
    lead = " " * indent
    pieces = _split(statement, width - indent - 2, width - indent - 8)
    lines = [lead + pieces[0]]
    for piece in pieces[1:]:
        lines[-1] += " &"
        lines.append(f"{lead}    & {piece}")
    return lines


def wrap_fixed(statement: str, indent: int) -> list[str]:
    """A fixed-form statement in columns 7-72, continued with ``&`` in column 6."""
    lead = " " * (6 + indent)
    pieces = _split(statement, FIXED_WIDTH - 6 - indent, FIXED_WIDTH - 6 - indent - 6)
    lines = [lead + pieces[0]]
    for piece in pieces[1:]:
        lines.append(f"     &{' ' * (indent + 6)}{piece}")
    return lines


def wrap_comment(text: str, lead: str, width: int) -> list[str]:
    """A comment paragraph as lines of at most ``width`` starting with ``lead``."""
    words = text.split()
    lines: list[str] = []
    line = lead.rstrip()
    for word in words:
        candidate = f"{line} {word}" if line != lead.rstrip() else f"{lead}{word}"
        if len(candidate) > width and line != lead.rstrip():
            lines.append(line)
            line = f"{lead}{word}"
        else:
            line = candidate
    lines.append(line)
    return lines


def _chunks(text: str, size: int) -> list[str]:
    """Split message text after blanks into chunks of at most about ``size`` characters;
    joined again they give ``text`` exactly."""
    chunks: list[str] = []
    for word in re.findall(r"\S+\s*|\s+", text):
        if chunks and len(chunks[-1]) + len(word) <= size:
            chunks[-1] += word
        else:
            chunks.append(word)
    return chunks


def free_string(text: str) -> str:
    """A free-form character expression: double-quoted chunks joined by ``//``."""
    return " // ".join('"' + c.replace('"', '""') + '"' for c in _chunks(text, 70))


def fixed_string(text: str) -> str:
    """A FORTRAN 77 character expression: apostrophe-quoted chunks joined by ``//``."""
    return " // ".join("'" + c.replace("'", "''") + "'" for c in _chunks(text, 48))
