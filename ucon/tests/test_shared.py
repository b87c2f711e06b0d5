"""Shared helpers generated once, and the constants that say which outputs can be non-zero."""

from __future__ import annotations

import dataclasses
import functools
import re
import unittest

import sympy

import ucon
from ucon.__main__ import PROJECT_ROOT
from ucon.derive import derive, simplified, table
from ucon.fortran import lower, render_legacy, render_module
from ucon.messages import IDRSEL_MESSAGE, IFLAG_MESSAGE, PART_MESSAGE
from ucon.module_writer import CONTRACT_NAMES, HELPER_MODULE, HELPER_NAMES
from ucon.rules import RESERVED_NAMES
from ucon.spec import TIME, Constraint, ConstraintSpec, Parameter, Variable
from ucon.tests.test_generate import derivatives as derived

#: The hand-written module every generated module uses.
HELPER_PATH = PROJECT_ROOT / "src/adams/rollcon_ucosub_helpers.f90"

x, xdot, psi = sympy.symbols("x xdot psi", real=True)
rate = sympy.Symbol("rate", real=True)


def mixed_spec() -> ConstraintSpec:
    """Two components that differ: F1 holonomic with an explicit time, F2 a velocity
    constraint free of the time."""
    return ConstraintSpec(
        name="mixed", title="mixed", summary="A constraint for the tests.",
        variables=(Variable(x, 11), Variable(psi, 14), Variable(xdot, 21)),
        parameters=(Parameter(rate, 5, "rate w", "rad/s"),),
        constraints=(Constraint(x - sympy.sin(rate * TIME) * psi, "first"),
                     Constraint(xdot - rate * psi + x, "second")))


@functools.lru_cache(maxsize=None)
def module_named(name: str) -> str:
    """The generated module of a spec of ucon/specs/, once per test run."""
    return render_module(lower(derived(name)))


def module_of(spec: ConstraintSpec) -> str:
    """The generated module's text."""
    return render_module(lower(derive(spec)))


def code_lines(text: str) -> str:
    """The module's text without its comment lines."""
    return "\n".join(line for line in text.splitlines() if not line.lstrip().startswith("!"))


class SharedHelpersTest(unittest.TestCase):
    """The checks every module shares live in rollcon_ucosub_helpers, once."""

    def test_modules_use_the_helpers_and_define_none(self) -> None:
        for name in ucon.spec_names():
            text = module_named(name)
            with self.subTest(name=name):
                self.assertIn(f"use {HELPER_MODULE}, only : ", text)
                for procedure in ("is_whole", "selectors_valid", "read_par_head"):
                    self.assertNotRegex(text, rf"(function|subroutine) {procedure}\b")
                self.assertNotIn("ieee_is_finite", text)
                self.assertNotIn("to_text", text)

    def test_modules_import_only_what_they_use(self) -> None:
        for name in ucon.spec_names():
            text = code_lines(module_named(name))
            uses = re.findall(r"^    use (\w+), only : (.*(?:\n        & .*)*)", text, re.M)
            imported = [n.strip() for _, names in uses
                        for n in names.replace("&", "").replace("\n", " ").split(",")]
            body = text.split("\ncontains\n", 1)[1]
            with self.subTest(name=name):
                self.assertIn("wp", imported)
                for symbol in imported:
                    self.assertRegex(body, rf"\b{symbol}\b", symbol)

    def test_fixed_form_stays_self_contained(self) -> None:
        for name in ucon.spec_names():
            legacy = render_legacy(lower(derived(name)))
            with self.subTest(name=name):
                self.assertNotRegex(legacy, r"(?im)^      USE ")
                self.assertIn("IDRSEL must be", legacy)
                self.assertIn("PAR(1) (part id)", legacy)

    def test_helper_texts_are_those_of_the_fixed_form(self) -> None:
        helper = HELPER_PATH.read_text(encoding="utf-8")
        for text in (IDRSEL_MESSAGE, IFLAG_MESSAGE, PART_MESSAGE):
            self.assertIn(f'"{text}"', helper)
        for symbol in HELPER_NAMES:
            self.assertRegex(helper, rf"public :: .*\b{symbol}\b")

    def test_names_the_module_imports_are_reserved(self) -> None:
        for symbol in HELPER_NAMES + CONTRACT_NAMES:
            self.assertIn(symbol, RESERVED_NAMES)


class OutputConstantsTest(unittest.TestCase):
    """<spec>_time_free, <spec>_holonomic and their per-component arrays."""

    def test_values_of_the_specs(self) -> None:
        expected = {"rolling_disk": ([True] * 3, [False] * 3),
                    "rolling_sphere": ([True] * 3, [False] * 3),
                    "turntable_disk": ([False, False, True], [False] * 3),
                    "knife_edge": ([True], [False]),
                    "disk_height": ([True], [True]),
                    "turntable_ball": ([True] * 3, [False] * 3),
                    "chaplygin_sled": ([True], [False]),
                    "planar_hold": ([True] * 3, [True] * 3)}
        # the joint primitives and CONVEL's homokinetic condition: positions only, no time;
        # to ground and between two parts
        for primitive, count in (("atpoint", 3), ("inline", 2), ("inplane", 1),
                                 ("parallel_axes", 2), ("perpendicular", 1),
                                 ("orientation", 3), ("homokinetic", 1)):
            for prefix in ("gnd_", "jp_"):
                expected[prefix + primitive] = ([True] * count, [True] * count)
        # the angles a MOTION drives: two components (rotation, tilt), positions only; the
        # MOTION's time part is the driver's (rollcon_motion)
        for prefix in ("gnd_", "jp_"):
            expected[prefix + "motion_angle"] = ([True] * 2, [True] * 2)
        self.assertEqual(sorted(expected), ucon.spec_names())
        for name, (time_free, holonomic) in expected.items():
            derivatives = derived(name)
            components = range(1, len(time_free) + 1)
            with self.subTest(name=name):
                self.assertEqual([derivatives.time_free(k) for k in components], time_free)
                self.assertEqual([derivatives.holonomic(k) for k in components], holonomic)

    def test_time_free_is_f_without_time(self) -> None:
        for name in ucon.spec_names():
            spec = ucon.load_spec(name)
            derivatives = derived(name)
            for k, constraint in enumerate(spec.constraints, start=1):
                # a spec that asks for no simplification (its entries short as written: the
                # joint primitives, a MOTION's angles) is judged as written, as derive does
                expression = constraint.expression
                if spec.simplify:
                    expression = simplified(expression)
                with self.subTest(name=name, component=k):
                    self.assertEqual(derivatives.time_free(k), not expression.has(TIME))

    def test_components_that_differ(self) -> None:
        text = module_of(mixed_spec())
        self.assertIn("logical, parameter :: mixed_time_free = .false.", text)
        self.assertIn("logical, parameter :: mixed_component_time_free(mixed_ncomponents) = "
                      "[.false., .true.]", text)
        self.assertIn("logical, parameter :: mixed_holonomic = .false.", text)
        self.assertIn("logical, parameter :: mixed_component_holonomic(mixed_ncomponents) = "
                      "[.true., .false.]", text)
        self.assertRegex(text, r"public :: mixed_time_free, mixed_component_time_free, "
                               r"mixed_holonomic, &\n        & mixed_component_holonomic")
        lines = table(derive(mixed_spec())).splitlines()
        self.assertEqual(lines[-2], "time-free (no dF/dt, d2F/dt2, d2F/dt dq): F2")
        self.assertEqual(lines[-1], "holonomic (no velocity): F1")

    def test_single_component_position_constraint(self) -> None:
        spec = dataclasses.replace(mixed_spec(), name="still", variables=mixed_spec().variables[:2],
                                   parameters=(Parameter(rate, 4, "rate w", "rad/s"),),
                                   constraints=(Constraint(x - rate * psi, "only"),))
        text = module_of(spec)
        self.assertIn("logical, parameter :: still_time_free = .true.", text)
        self.assertIn("logical, parameter :: still_holonomic = .true.", text)
        self.assertIn("still_component_holonomic(still_ncomponents) = [.true.]", text)


if __name__ == "__main__":
    unittest.main()
