"""The generator's output: entry counts, physics, printing, wrapping, determinism, commands."""

from __future__ import annotations

import contextlib
import functools
import io
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import sympy
from sympy import cos, sin

import ucon
from ucon.__main__ import PROJECT_ROOT, main
from ucon.derive import Derivatives, derive, table
from ucon.fortran import (LegacyPrinter, ModulePrinter, legacy_path, lower, module_path,
                          render_legacy, render_module, wrap_fixed, wrap_free)
from ucon.spec import TIME

#: Two ``python -m ucon write --out DIR`` runs with different hash seeds, started when the
#: module loads so that they run while the in-process tests do: (process, DIR) pairs.
_WRITES: list[tuple[subprocess.Popen[bytes], tempfile.TemporaryDirectory[str]]] = []


def setUpModule() -> None:
    """Start the two write runs of DeterminismTest."""
    for seed in ("1", "2"):
        out = tempfile.TemporaryDirectory()
        environment = dict(os.environ, PYTHONHASHSEED=seed)
        process = subprocess.Popen([sys.executable, "-m", "ucon", "write", "--out", out.name],
                                   cwd=PROJECT_ROOT, env=environment,
                                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        _WRITES.append((process, out))


def tearDownModule() -> None:
    """Stop the write runs if still going, remove their directories."""
    for process, out in _WRITES:
        if process.poll() is None:
            process.kill()
        process.communicate()
        out.cleanup()


@functools.lru_cache(maxsize=None)
def derivatives(name: str) -> Derivatives:
    """The derived entries of a spec, once per test run."""
    return derive(ucon.load_spec(name))


@functools.lru_cache(maxsize=None)
def generated(name: str) -> tuple[tuple[str, str], ...]:
    """The generated files of a spec (as ucon.generate makes them), once per test run."""
    program = lower(derivatives(name))
    return ((module_path(program.spec), render_module(program)),
            (legacy_path(program.spec), render_legacy(program)))


def symbols_of(name: str) -> dict[str, sympy.Symbol]:
    """The declared symbols of a spec by name."""
    return {s.name: s for s in ucon.load_spec(name).symbols}


class DerivationTest(unittest.TestCase):
    """Counts of non-zero entries and the physics of the specs."""

    def test_rolling_disk_has_49_entries(self) -> None:
        entries = derivatives("rolling_disk")
        self.assertEqual(entries.count("value"), 3)
        self.assertEqual(entries.count("dq"), 15)
        self.assertEqual(entries.count("dqdq"), 31)
        for kind in ("time_part", "dt", "dtt", "dtdq"):
            self.assertEqual(entries.count(kind), 0, kind)
        self.assertEqual(entries.count(), 49)
        self.assertIn("+ 31 d2F/dq dq = 49", table(entries))

    def test_rolling_disk_is_design_section_5(self) -> None:
        s = symbols_of("rolling_disk")
        xdot, ydot, zdot, psi, theta = (s[n] for n in ("xdot", "ydot", "zdot", "psi", "theta"))
        psidot, thetadot, phidot, r = (s[n] for n in ("psidot", "thetadot", "phidot", "radius"))
        design = [
            xdot + r * cos(psi) * (phidot + psidot * cos(theta))
            - r * thetadot * sin(psi) * sin(theta),
            ydot + r * sin(psi) * (phidot + psidot * cos(theta))
            + r * thetadot * cos(psi) * sin(theta),
            zdot - r * thetadot * cos(theta),
        ]
        for k, expected in enumerate(design, start=1):
            value = derivatives("rolling_disk").of(k, "value")[0].expression
            self.assertEqual(sympy.simplify(value - expected), 0, f"F{k}")

    def test_rolling_sphere_is_its_docstring(self) -> None:
        s = symbols_of("rolling_sphere")
        xdot, ydot, zdot, psi, theta = (s[n] for n in ("xdot", "ydot", "zdot", "psi", "theta"))
        thetadot, phidot, r = (s[n] for n in ("thetadot", "phidot", "radius"))
        design = [xdot + r * (phidot * sin(theta) * cos(psi) - thetadot * sin(psi)),
                  ydot + r * (phidot * sin(theta) * sin(psi) + thetadot * cos(psi)),
                  zdot]
        for k, expected in enumerate(design, start=1):
            value = derivatives("rolling_sphere").of(k, "value")[0].expression
            self.assertEqual(sympy.simplify(value - expected), 0, f"F{k}")
        self.assertEqual(derivatives("rolling_sphere").count("dt"), 0)

    def test_turntable_exercises_every_time_derivative(self) -> None:
        entries = derivatives("turntable_disk")
        self.assertEqual(entries.count("time_part"), 2)
        self.assertEqual(entries.count("dt"), 2)
        self.assertEqual(entries.count("dtt"), 2)
        self.assertEqual(entries.count("dtdq"), 6)
        s = symbols_of("turntable_disk")
        rate = s["rate_mean"] + s["rate_ripple"] * sin(s["ripple_frequency"] * TIME)
        f1 = entries.of(1, "time_part")[0].expression
        f2 = entries.of(2, "time_part")[0].expression
        self.assertEqual(sympy.simplify(f1 + s["centre_y"] * rate), 0)
        self.assertEqual(sympy.simplify(f2 - s["centre_x"] * rate), 0)

    def test_turntable_reduces_to_the_disk_on_a_still_table(self) -> None:
        s = symbols_of("turntable_disk")
        still = {s["rate_mean"]: 0, s["rate_ripple"]: 0}
        disk = symbols_of("rolling_disk")
        rename = {disk[name]: s[name] for name in disk}
        for k in (1, 2, 3):
            table_value = derivatives("turntable_disk").of(k, "value")[0].expression
            disk_value = derivatives("rolling_disk").of(k, "value")[0].expression
            self.assertEqual(sympy.simplify(table_value.subs(still) - disk_value.xreplace(rename)),
                             0, f"F{k}")

    def test_knife_edge_and_disk_height(self) -> None:
        s = symbols_of("knife_edge")
        value = derivatives("knife_edge").of(1, "value")[0].expression
        self.assertEqual(sympy.simplify(value - (-s["xdot"] * sin(s["psi"])
                                                 + s["ydot"] * cos(s["psi"]))), 0)
        s = symbols_of("disk_height")
        value = derivatives("disk_height").of(1, "value")[0].expression
        self.assertEqual(value - (s["z"] - s["radius"] * sin(s["theta"])), 0)
        self.assertEqual(derivatives("disk_height").count(), 4)

    def test_second_partials_are_stored_once_per_pair(self) -> None:
        for name in ucon.spec_names():
            for entry in derivatives(name).entries:
                if entry.output == "dqdq":
                    self.assertLessEqual(entry.row, entry.column, name)


class PrintingTest(unittest.TestCase):
    """Literals, wrapping, and the shape of the generated files."""

    def test_module_literals(self) -> None:
        x = sympy.Symbol("x", real=True)
        printer = ModulePrinter()
        self.assertEqual(printer.expression(2 * x), "2.0_wp*x")
        self.assertEqual(printer.expression(x / 2), "(1.0_wp/2.0_wp)*x")
        self.assertEqual(printer.expression(sympy.Float("1e-5") * x), "1.0e-5_wp*x")
        self.assertEqual(printer.expression(x**2), "x**2")
        self.assertEqual(printer.expression(1 / x), "1.0_wp/x")
        self.assertEqual(printer.expression(x**-3), "x**(-3)")
        self.assertEqual(printer.expression(sympy.sqrt(x)), "sqrt(x)")
        self.assertEqual(printer.expression(sympy.pi * x), "3.141592653589793_wp*x")

    def test_legacy_literals(self) -> None:
        x = sympy.Symbol("x", real=True)
        printer = LegacyPrinter()
        self.assertEqual(printer.expression(2 * x), "2.0D0*X")
        self.assertEqual(printer.expression(sympy.Float("1e-5") * sympy.cos(x)),
                         "1.0D-5*COS(X)")
        self.assertEqual(printer.expression(sympy.pi), "3.141592653589793D0")

    def test_wrapping_keeps_the_statement(self) -> None:
        terms = [f"alpha{i}*cos(beta{i})**2" for i in range(30)]
        statement = "value = " + " + ".join(terms)
        free = wrap_free(statement, 8)
        self.assertTrue(all(len(line) <= 100 for line in free))
        joined = "".join(line.strip().removesuffix("&").removeprefix("& ") for line in free)
        self.assertEqual(joined.replace(" ", ""), statement.replace(" ", ""))
        fixed = wrap_fixed(statement.upper(), 3)
        self.assertTrue(all(len(line) <= 72 for line in fixed))
        self.assertTrue(all(line.startswith("     &") for line in fixed[1:]))
        joined = "".join(line[6:] for line in fixed)
        self.assertEqual(joined.replace(" ", ""), statement.upper().replace(" ", ""))

    def test_wrapping_never_splits_a_string(self) -> None:
        statement = 'message = "' + "word " * 10 + '" // "' + "more " * 10 + '" // to_text(x)'
        for line in wrap_free(statement, 12, width=80):
            self.assertEqual(line.count('"') % 2, 0, line)
        with self.assertRaises(ValueError):
            wrap_free(statement, 12, width=50)

    def test_file_shapes(self) -> None:
        for name in ucon.spec_names():
            files = dict(generated(name))
            module = files[f"src/ucosubs/generated/rollcon_gen_{name}.f90"].splitlines()
            legacy = files[f"ucon/adams/{name}/ucosub.f"].splitlines()
            with self.subTest(name=name):
                self.assertEqual(module[:2], [
                    f"! Generated by ucon from ucon/specs/{name}.py -- do not edit.",
                    "! Regenerate with: python -m ucon write"])
                self.assertIn(f"module rollcon_gen_{name}", module)
                # a long spec name wraps the signature onto a continuation line
                joined = "\n".join(module).replace(" &\n        & ", " ").splitlines()
                self.assertIn(f"    subroutine {name}_ucosub(id, time, q, par, npar, idrsel, "
                              "iflag, scalar, array, xmatrx)", joined)
                self.assertTrue(all(len(line) <= 100 for line in module))
                self.assertEqual(legacy[:2], [
                    f"C Generated by ucon from ucon/specs/{name}.py -- do not edit.",
                    "C Regenerate with: python -m ucon write"])
                self.assertEqual(sum(line.startswith("      SUBROUTINE ") for line in legacy), 1)
                for line in legacy:
                    self.assertLessEqual(len(line), 72, line)
                    self.assertNotIn("\t", line)
                    if not line.startswith("C"):
                        self.assertTrue(line[:5].strip().isdigit() or not line[:5].strip(),
                                        line)
                        self.assertIn(line[5], " &", line)

    def test_unused_time_is_not_passed_on(self) -> None:
        disk = dict(generated("rolling_disk"))["src/ucosubs/generated/rollcon_gen_rolling_disk.f90"]
        self.assertIn("call evaluate(q, par, component,", disk)
        table_disk = dict(generated("turntable_disk"))["src/ucosubs/generated/rollcon_gen_turntable_disk.f90"]
        self.assertIn("call evaluate(time, q, par, component,", table_disk)


class DeterminismTest(unittest.TestCase):
    """Two ``write`` runs, in processes with different hash seeds, give the same bytes."""

    def test_two_writes_are_byte_identical(self) -> None:
        for process, _ in _WRITES:
            _, errors = process.communicate(timeout=900)
            self.assertEqual(process.returncode, 0, errors.decode())
        (_, first), (_, second) = _WRITES
        first_files = sorted(p.relative_to(first.name) for p in Path(first.name).rglob("*")
                             if p.is_file())
        second_files = sorted(p.relative_to(second.name) for p in Path(second.name).rglob("*")
                              if p.is_file())
        self.assertEqual(first_files, second_files)
        # two files per spec, the catalog of them all, and the reduced disk's and bicycle's
        # modules
        self.assertEqual(len(first_files), 2 * len(ucon.spec_names()) + 3)
        for relative in first_files:
            self.assertEqual((Path(first.name) / relative).read_bytes(),
                             (Path(second.name) / relative).read_bytes(), str(relative))
        for name in ucon.spec_names():
            for path, text in generated(name):
                self.assertEqual((Path(first.name) / path).read_text(), text, path)


class CommandLineTest(unittest.TestCase):
    """``python -m ucon``: help, write, check, table, errors."""

    def run_main(self, *arguments: str) -> tuple[int, str, str]:
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                status = main(list(arguments))
            except SystemExit as exit:
                status = int(exit.code or 0)
        return status, out.getvalue(), err.getvalue()

    def test_help(self) -> None:
        for command in ([], ["write"], ["check"], ["table"]):
            status, out, _ = self.run_main(*command, "--help")
            self.assertEqual(status, 0)
            self.assertIn("usage: python -m ucon", out)

    def test_write_check_and_diff(self) -> None:
        with tempfile.TemporaryDirectory() as root:
            status, out, _ = self.run_main("write", "--out", root, "knife_edge")
            self.assertEqual(status, 0)
            self.assertIn("wrote src/ucosubs/generated/rollcon_gen_knife_edge.f90", out)
            status, out, _ = self.run_main("write", "--out", root, "knife_edge")
            self.assertIn("unchanged ucon/adams/knife_edge/ucosub.f", out)
            status, out, _ = self.run_main("check", "--root", root, "knife_edge")
            self.assertEqual(status, 0, out)
            path = Path(root) / "src/ucosubs/generated/rollcon_gen_knife_edge.f90"
            path.write_text(path.read_text().replace("cos(psi)", "sin(psi)"))
            status, out, _ = self.run_main("check", "--root", root, "knife_edge")
            self.assertEqual(status, 1)
            self.assertIn("+++ src/ucosubs/generated/rollcon_gen_knife_edge.f90 (regenerated)", out)
            self.assertIn("-", out)
            path.unlink()
            status, out, _ = self.run_main("check", "--root", root, "knife_edge")
            self.assertEqual(status, 1)
            self.assertIn("missing: src/ucosubs/generated/rollcon_gen_knife_edge.f90", out)

    def test_table(self) -> None:
        status, out, _ = self.run_main("table", "disk_height")
        self.assertEqual(status, 0)
        self.assertIn("disk_height: 1 constraint(s) over 2 variables (z theta)", out)
        self.assertIn("= 4", out)

    def test_unknown_spec(self) -> None:
        status, _, err = self.run_main("table", "no_such_spec")
        self.assertEqual(status, 2)
        self.assertIn("ucon: error: no spec 'no_such_spec'", err)


if __name__ == "__main__":
    unittest.main()
