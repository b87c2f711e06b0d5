"""Every kind of bad spec is rejected with a message that names the spec and the culprit."""

from __future__ import annotations

import dataclasses
import unittest
from typing import Any

import sympy

from ucon.derive import derive
from ucon.spec import (TIME, Constraint, ConstraintSpec, Parameter, Variable, validate)

xdot, ydot, zdot = sympy.symbols("xdot ydot zdot", real=True)
psi, theta = sympy.symbols("psi theta", real=True)
psidot, thetadot = sympy.symbols("psidot thetadot", real=True)
radius = sympy.Symbol("radius", positive=True)


def small_spec(**changes: Any) -> ConstraintSpec:
    """A valid two-component spec, with some fields replaced."""
    spec = ConstraintSpec(
        name="sample",
        title="sample",
        summary="A constraint for the tests.",
        variables=(Variable(xdot, 21), Variable(ydot, 22), Variable(psi, 14)),
        parameters=(Parameter(radius, 5, "radius R", "m", check="positive"),),
        constraints=(Constraint(xdot + radius * sympy.cos(psi) * ydot, "first"),
                     Constraint(ydot - radius * sympy.sin(psi), "second")),
    )
    return dataclasses.replace(spec, **changes)


def with_expression(expression: sympy.Expr) -> ConstraintSpec:
    """The small spec whose second component is replaced."""
    first = small_spec().constraints[0]
    return small_spec(constraints=(first, Constraint(expression, "second")))


class BadSpecTest(unittest.TestCase):
    """Each case: the spec, and a fragment its ValueError must contain."""

    def assert_rejected(self, spec: ConstraintSpec, *fragments: str) -> None:
        with self.assertRaises(ValueError) as caught:
            validate(spec)
        message = str(caught.exception)
        self.assertTrue(message.startswith(f"spec '{spec.name}'"), message)
        for fragment in fragments:
            self.assertIn(fragment, message)

    def test_valid_spec_passes(self) -> None:
        validate(small_spec())

    def test_undeclared_symbol(self) -> None:
        rho = sympy.Symbol("rho", real=True)
        self.assert_rejected(with_expression(ydot - rho), "constraint 2",
                             "symbol 'rho' is not a declared variable, parameter or the time")

    def test_symbol_with_other_assumptions(self) -> None:
        plain_psi = sympy.Symbol("psi")
        self.assert_rejected(with_expression(ydot - radius * sympy.sin(plain_psi)),
                             "symbol 'psi'", "declared, but with other assumptions")

    def test_time_is_the_only_extra_symbol(self) -> None:
        t = sympy.Symbol("t", real=True)
        self.assert_rejected(with_expression(ydot - radius * t), "symbol 't'")
        validate(with_expression(ydot - radius * TIME))

    def test_product_of_velocities(self) -> None:
        self.assert_rejected(with_expression(ydot + radius * xdot * ydot),
                             "not linear in the velocities", "term radius*xdot*ydot")

    def test_square_of_a_velocity(self) -> None:
        self.assert_rejected(with_expression(ydot + psi * xdot**2), "term psi*xdot**2")

    def test_function_of_a_velocity(self) -> None:
        self.assert_rejected(with_expression(ydot + radius * sympy.sin(xdot)),
                             "term radius*sin(xdot)")

    def test_velocity_in_a_product_of_sums(self) -> None:
        self.assert_rejected(with_expression((xdot + 1) * (ydot + psi)), "term xdot*ydot")

    def test_linear_with_position_coefficients_passes(self) -> None:
        validate(with_expression(sympy.cos(psi) * xdot + sympy.sin(psi)**2 * ydot + TIME))

    def test_more_than_30_variables(self) -> None:
        codes = [11, 12, 13, 14, 15, 16, 21, 22, 23, 24, 25, 26]
        many = tuple(Variable(sympy.Symbol(f"v{i}", real=True), codes[i % 12])
                     for i in range(31))
        self.assert_rejected(small_spec(variables=many),
                             "declares 31 variables; UCOVAR accepts at most 30")

    def test_more_than_30_par(self) -> None:
        parameters = tuple(Parameter(sympy.Symbol(f"p{i}", real=True), 5 + i, f"p{i}", "m")
                           for i in range(26))
        expression = ydot + sympy.Add(*[p.symbol for p in parameters])
        spec = small_spec(parameters=parameters,
                          constraints=(Constraint(xdot + psi, "first"),
                                       Constraint(expression, "second")))
        self.assert_rejected(spec, "needs NPAR = 31", "at most 30 constants")

    def test_unknown_code(self) -> None:
        variables = (Variable(xdot, 21), Variable(ydot, 17), Variable(psi, 14))
        self.assert_rejected(small_spec(variables=variables),
                             "variable 'ydot' has unknown code 17")

    def test_repeated_code(self) -> None:
        variables = (Variable(xdot, 21), Variable(ydot, 21), Variable(psi, 14))
        self.assert_rejected(small_spec(variables=variables),
                             "code 21 is declared twice ('xdot' and 'ydot')")

    def test_parameter_at_wrong_par_index(self) -> None:
        parameters = (Parameter(radius, 9, "radius R", "m"),)
        self.assert_rejected(small_spec(parameters=parameters),
                             "parameter 'radius' is at PAR(9); expected PAR(5)")

    def test_unknown_parameter_check(self) -> None:
        parameters = (Parameter(radius, 5, "radius R", "m", check="nonnegative"),)
        self.assert_rejected(small_spec(parameters=parameters),
                             "parameter 'radius' has check 'nonnegative'")

    def test_unsupported_function(self) -> None:
        self.assert_rejected(with_expression(ydot - sympy.Abs(psi)),
                             "'Abs(psi)' (Abs) is not supported")

    def test_undefined_function(self) -> None:
        f = sympy.Function("f")
        self.assert_rejected(with_expression(ydot - f(TIME)), "'f(time)'", "is not supported")

    def test_complex_number(self) -> None:
        self.assert_rejected(with_expression(ydot - sympy.I * psi), "is not supported")

    def test_not_a_sympy_expression(self) -> None:
        self.assert_rejected(with_expression(1.5), "is not a SymPy expression")

    def test_no_constraint(self) -> None:
        self.assert_rejected(small_spec(constraints=()), "declares no constraint")

    def test_constraint_free_of_variables(self) -> None:
        self.assert_rejected(with_expression(radius * TIME), "depends on no declared variable")

    def test_unused_variable(self) -> None:
        variables = small_spec().variables + (Variable(thetadot, 25),)
        parameters = (Parameter(radius, 6, "radius R", "m"),)
        self.assert_rejected(small_spec(variables=variables, parameters=parameters),
                             "variable 'thetadot' (code 25) appears in no constraint")

    def test_unused_parameter(self) -> None:
        extra = Parameter(sympy.Symbol("mass", positive=True), 6, "mass", "kg")
        parameters = small_spec().parameters + (extra,)
        self.assert_rejected(small_spec(parameters=parameters),
                             "parameter 'mass' (PAR(6)) appears in no constraint")

    def test_reserved_names(self) -> None:
        for name in ("q", "time", "cse3", "sin", "scalar"):
            symbol = sympy.Symbol(name, real=True)
            variables = (Variable(xdot, 21), Variable(ydot, 22), Variable(symbol, 14))
            spec = small_spec(variables=variables,
                              constraints=(Constraint(xdot + symbol, "first"),
                                           Constraint(ydot - radius, "second")))
            with self.subTest(name=name):
                self.assert_rejected(spec, f"symbol name '{name}' is reserved")

    def test_name_that_is_no_lowercase_fortran_name(self) -> None:
        for name in ("Psi", "2psi", "psi-dot", "psi_" + "x" * 30):
            symbol = sympy.Symbol(name, real=True)
            variables = (Variable(xdot, 21), Variable(ydot, 22), Variable(symbol, 14))
            spec = small_spec(variables=variables,
                              constraints=(Constraint(xdot + symbol, "first"),
                                           Constraint(ydot - radius, "second")))
            with self.subTest(name=name):
                self.assert_rejected(spec, f"symbol name '{name}' is not a lowercase Fortran")

    def test_bad_spec_names(self) -> None:
        self.assert_rejected(small_spec(name="Sample"), "name must be lowercase")
        self.assert_rejected(small_spec(name="a_very_long_spec_name"),
                             "at most 18 keep the header of ucosub.f within column 72")

    def test_text_must_be_ascii(self) -> None:
        self.assert_rejected(small_spec(title="rolling \u03c8"), "title must be one non-empty")
        self.assert_rejected(small_spec(summary=""), "summary must be one non-empty")

    def test_derive_validates_first(self) -> None:
        with self.assertRaises(ValueError):
            derive(with_expression(ydot * xdot))


if __name__ == "__main__":
    unittest.main()
