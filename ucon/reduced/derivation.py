"""The rolling disk in minimal coordinates, derived with Kane's method.

Generalized coordinates ψ, θ, φ, X, Y (the 3-1-3 Euler angles of the disk and its centre's
ground position; Z = R sin θ is substituted, the no-penetration condition being holonomic).
Generalized speeds u1 = θ̇, u2 = ψ̇, u3 = ω₃ = φ̇ + ψ̇ cos θ (independent) and u4 = Ẋ,
u5 = Ẏ (dependent): the no-slip conditions at the contact point, v_C · e_X = v_C · e_Y = 0,
are nonholonomic velocity constraints that KanesMethod eliminates. The vertical component of
v_C vanishes identically with Ż = R cos θ θ̇ (checked in the tests). Loads: gravity at the
centre and the strike of the coin scene, a horizontal force F along +Y at the top of the rim
(the point G + R e_y2, farthest from the ground), whose generalized force Kane's method forms
from that point's partial velocities. docs/design.md §3, §5 state the conventions.

The result is the first-order system of the reduced state
y = (θ, θ̇, ψ̇, ω₃, ψ, φ, X, Y), its Jacobian ∂ẏ/∂y, the energy, and the maps to and from the
full ADAMS state (q, u) of the part.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import sympy
from sympy import cos, sin
from sympy.physics.mechanics import (KanesMethod, Point, ReferenceFrame, RigidBody,
                                     dynamicsymbols, inertia)

__all__ = ["PARAMETERS", "STATES", "ReducedDisk", "derive_reduced"]

#: Parameters, in the order of the generated routines' arguments: moment of inertia about a
#: diameter A and about the axis C [kg m²], mass m [kg], radius R [m], gravity g [m/s²].
PARAMETERS = sympy.symbols("inertia_diameter inertia_axis mass radius gravity", positive=True)
#: Horizontal strike force along +Y at the top of the rim [N], given at each evaluation.
STRIKE = sympy.Symbol("strike", real=True)
#: The reduced state y = (θ, θ̇, ψ̇, ω₃, ψ, φ, X, Y), as plain symbols.
STATES = sympy.symbols("theta theta_rate psi_rate spin psi phi x_centre y_centre", real=True)


@dataclass(frozen=True)
class ReducedDisk:
    """The derived equations, every expression in ``STATES``, ``PARAMETERS`` and ``STRIKE``."""

    #: ẏ, eight expressions
    rate: tuple[sympy.Expr, ...]
    #: ∂ẏ/∂y, 8 × 8
    jacobian: sympy.Matrix
    #: The full state of the part: q = (X, Y, Z, ψ, θ, φ), u = q̇
    full_q: tuple[sympy.Expr, ...]
    full_u: tuple[sympy.Expr, ...]
    #: Kinetic plus potential energy [J]
    energy: sympy.Expr
    #: Vertical velocity of the contact point, which must vanish identically
    contact_vertical_velocity: sympy.Expr


@functools.lru_cache(maxsize=1)
def derive_reduced() -> ReducedDisk:
    """Derive the reduced equations (a few seconds)."""
    inertia_a, inertia_c, mass, radius, gravity = PARAMETERS
    psi, theta, phi, x, y = dynamicsymbols("psi theta phi x y")
    u1, u2, u3, u4, u5 = dynamicsymbols("u1:6")
    ground = ReferenceFrame("N")
    heading = ground.orientnew("H", "Axis", (psi, ground.z))
    tilt = heading.orientnew("T", "Axis", (theta, heading.x))
    body = tilt.orientnew("D", "Axis", (phi, tilt.z))
    # ω = ψ̇ e_Z + θ̇ e_x1 + φ̇ e_z2 with φ̇ = ω₃ − ψ̇ cos θ (docs/design.md §3)
    body.set_ang_vel(ground, u2*ground.z + u1*heading.x + (u3 - u2*cos(theta))*tilt.z)
    origin = Point("O")
    origin.set_vel(ground, 0)
    centre = origin.locatenew("G", x*ground.x + y*ground.y + radius*sin(theta)*ground.z)
    centre.set_vel(ground, u4*ground.x + u5*ground.y + radius*cos(theta)*u1*ground.z)
    contact = centre.locatenew("C", -radius*tilt.y)
    contact.v2pt_theory(centre, ground, body)
    top = centre.locatenew("P", radius*tilt.y)
    top.v2pt_theory(centre, ground, body)
    no_slip = [contact.vel(ground).dot(ground.x), contact.vel(ground).dot(ground.y)]
    kinematics = [psi.diff() - u2, theta.diff() - u1, phi.diff() - (u3 - u2*cos(theta)),
                  x.diff() - u4, y.diff() - u5]
    disk = RigidBody("disk", centre, body, mass,
                     (inertia(tilt, inertia_a, inertia_a, inertia_c), centre))
    loads = [(centre, -mass*gravity*ground.z), (top, STRIKE*ground.y)]
    kane = KanesMethod(ground, q_ind=[psi, theta, phi, x, y], u_ind=[u1, u2, u3],
                       u_dependent=[u4, u5], kd_eqs=kinematics, velocity_constraints=no_slip)
    kane.kanes_equations([disk], loads)
    # the mass matrix holds the independent dynamic rows and the constraint rows
    accelerations = kane.mass_matrix.LUsolve(kane.forcing)
    dependent = sympy.solve(no_slip, [u4, u5], dict=True)[0]

    theta_s, theta_rate, psi_rate, spin, psi_s, phi_s, x_s, y_s = STATES
    plain = {u1: theta_rate, u2: psi_rate, u3: spin, psi: psi_s, theta: theta_s, phi: phi_s,
             x: x_s, y: y_s}

    def flat(expr: sympy.Expr) -> sympy.Expr:
        return sympy.simplify(sympy.sympify(expr).subs(plain))

    x_rate = flat(dependent[u4])
    y_rate = flat(dependent[u5])
    phi_rate = spin - psi_rate*cos(theta_s)
    rate = (theta_rate, flat(accelerations[0]), flat(accelerations[1]), flat(accelerations[2]),
            psi_rate, phi_rate, x_rate, y_rate)
    jacobian = sympy.Matrix(rate).jacobian(sympy.Matrix(STATES))
    full_q = (x_s, y_s, radius*sin(theta_s), psi_s, theta_s, phi_s)
    full_u = (x_rate, y_rate, radius*cos(theta_s)*theta_rate, psi_rate, theta_rate, phi_rate)
    speed_squared = x_rate**2 + y_rate**2 + (radius*cos(theta_s)*theta_rate)**2
    energy = (mass*speed_squared/2
              + (inertia_a*(theta_rate**2 + psi_rate**2*sin(theta_s)**2)
                 + inertia_c*spin**2)/2
              + mass*gravity*radius*sin(theta_s))
    vertical = flat(contact.vel(ground).dot(ground.z).subs(dependent))
    return ReducedDisk(rate=rate, jacobian=jacobian, full_q=full_q, full_u=full_u,
                       energy=energy, contact_vertical_velocity=vertical)
