"""The Whipple bicycle in minimal coordinates, derived with Kane's method.

The benchmark bicycle of Meijaard, Papadopoulos, Ruina and Schwab (2007): four rigid bodies
(rear wheel R, rear frame with rider B, front frame H, front wheel F), knife-edge wheels rolling
without slip on flat ground, in the paper's axes (x forward, y to the right, z down; origin at
the rear contact at t = 0) and with its parameters (``PARAMETERS``, the table
data/bicycle/benchmark.txt).

Generalized coordinates: yaw ψ (q3, about z), roll φ (q4, about the yawed x), pitch θ (q5,
about the rolled y: the rear frame B, whose axes are the paper's at the upright reference), the
rear wheel's angle θ_R (q6) and the front wheel's θ_F (q8) about their axles, and the steer δ
(q7, about the steer axis pointing down, tilted forward by λ from the vertical: δ > 0 turns the
front wheel to the right). The rear contact point's position (x, y) is ignorable: its velocity
follows from the rear wheel's no-slip, which fixes the rear axle's velocity as ω_R × (−r_R e_z
of the rolled frame); x and y are integrated from it.

Generalized speeds u_i = q̇_i, i = 3 … 8. Kane's equations of the six speeds (``KanesMethod``:
M_full u̇ = F_full, the push and gravity as loads), and the front wheel's contact, whose material
point has no velocity: three velocity constraints B(q) u = 0 (no slip along x and y, and the
vertical one, the time derivative of the holonomic contact condition h(φ, θ, δ) = 0 that fixes
the pitch). The dependent speeds are yaw, pitch and front wheel rates (u3, u5, u8), the
independent ones roll, rear wheel and steer rates (u4, u6, u7). The generated code solves, at
each evaluation, the pitch from h = 0 (Newton's method), B_dep u_dep = −B_ind u_ind, and Kane's
equations projected on the independent speeds by the nonholonomic partial velocities
T = [I; −B_dep⁻¹ B_ind] (three numeric solves of size 3): T^T M_full T u̇_ind =
T^T (F_full − M_full w), where w holds the dependent accelerations' part that B(q) u̇ + Ḃ u = 0
leaves when u̇_ind = 0. Symbolic inversion of B_dep is avoided: it would multiply the
expressions' size for nothing.

The load of the benchmark's run is a push on the rear frame at its centre of mass, along the
ADAMS dataset's +Y (the paper's −y), of ``PUSH`` newtons, given at each evaluation.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import sympy
from sympy.core.function import AppliedUndef
from sympy.physics.mechanics import (KanesMethod, Point, ReferenceFrame, RigidBody,
                                     dynamicsymbols, inertia)

__all__ = ["TABLE_NAMES", "PARAMETERS", "SPEEDS", "COORDINATES", "PUSH", "ReducedBicycle", "derive_bicycle"]

#: The parameters' names in data/bicycle/benchmark.txt (Meijaard et al. (2007), Table 1), in
#: the order of the generated routines' argument par
TABLE_NAMES = ("w", "c", "lambda", "g", "r_R", "m_R", "I_Rxx", "I_Ryy", "x_B", "z_B", "m_B",
               "I_Bxx", "I_Byy", "I_Bzz", "I_Bxz", "x_H", "z_H", "m_H", "I_Hxx", "I_Hyy",
               "I_Hzz", "I_Hxz", "r_F", "m_F", "I_Fxx", "I_Fyy")
#: The parameters as symbols, in that order (lower case: Fortran does not tell r_R from r_r)
PARAMETERS = sympy.symbols(" ".join("lam" if name == "lambda" else name.lower()
                                    for name in TABLE_NAMES), real=True)
#: Sideways push on the rear frame's centre of mass along the dataset's +Y (paper's -y) [N]
PUSH = sympy.Symbol("push", real=True)
#: The coordinates the expressions depend on, as plain symbols: yaw, roll, pitch, steer
COORDINATES = sympy.symbols("yaw roll pitch steer", real=True)
#: The six speeds (u3 ... u8): yaw, roll, pitch, rear wheel, steer, front wheel rates
SPEEDS = sympy.symbols("yaw_rate roll_rate pitch_rate rear_rate steer_rate front_rate",
                       real=True)
#: Placeholders of a vector of six (for M times a vector)
VECTOR = sympy.symbols("v1:7", real=True)
#: Which of SPEEDS are dependent (yaw, pitch, front wheel) and independent (roll, rear, steer)
DEPENDENT = (0, 2, 5)
INDEPENDENT = (1, 3, 4)


@dataclass(frozen=True)
class ReducedBicycle:
    """The derived expressions, in COORDINATES, SPEEDS, PARAMETERS and PUSH."""

    #: Holonomic contact condition h (the front contact's height, z down) [m] and dh/dpitch
    contact_height: sympy.Expr
    contact_height_pitch: sympy.Expr
    #: B (3 x 6): the front contact's material velocity (x, y, z) = B u
    constraint: sympy.Matrix
    #: Ḃ u (3): the velocity-product part of d(B u)/dt
    constraint_rate: sympy.Matrix
    #: Kane's equations of the six speeds: mass (6 x 6, symmetric) and forcing (6)
    mass: sympy.Matrix
    forcing: sympy.Matrix
    #: The rear contact's velocity (x, y) in the paper's ground axes [m/s]
    contact_velocity: tuple[sympy.Expr, sympy.Expr]
    #: Kinetic plus potential energy [J]
    energy: sympy.Expr


@functools.lru_cache(maxsize=1)
def derive_bicycle() -> ReducedBicycle:
    """Derive the equations (some seconds)."""
    (w, c, lam, g, r_r, m_r, i_rxx, i_ryy, x_b, z_b, m_b, i_bxx, i_byy, i_bzz, i_bxz,
     x_h, z_h, m_h, i_hxx, i_hyy, i_hzz, i_hxz, r_f, m_f, i_fxx, i_fyy) = PARAMETERS
    q3, q4, q5, q6, q7, q8 = dynamicsymbols("q3:9")
    u3, u4, u5, u6, u7, u8 = speeds = dynamicsymbols("u3:9")
    ground = ReferenceFrame("N")
    yawed = ground.orientnew("A", "Axis", (q3, ground.z))
    rolled = yawed.orientnew("R", "Axis", (q4, yawed.x))
    frame = rolled.orientnew("B", "Axis", (q5, rolled.y))
    rear_wheel = frame.orientnew("C", "Axis", (q6, frame.y))
    # the steer axis is the z axis of frame tilted by lam about its y (down, forward)
    tilted = frame.orientnew("D", "Axis", (lam, frame.y))
    fork = tilted.orientnew("H", "Axis", (q7, tilted.z))
    # the front frame's axes that are the paper's at the reference (its inertia is given there)
    fork_axes = fork.orientnew("E", "Axis", (-lam, fork.y))
    front_wheel = fork_axes.orientnew("F", "Axis", (q8, fork_axes.y))

    contact = Point("O")
    contact.set_vel(ground, 0)
    # rear wheel centre: the rear contact's material point is at rest
    rear_centre = contact.locatenew("RW", -r_r*rolled.z)
    rear_centre.set_vel(ground, rear_wheel.ang_vel_in(ground).cross(-r_r*rolled.z))
    frame_centre = rear_centre.locatenew("BO", x_b*frame.x + (z_b + r_r)*frame.z)
    frame_centre.v2pt_theory(rear_centre, ground, frame)
    # a point of the steer axis: where it meets the ground at the reference (trail c ahead)
    steer_point = rear_centre.locatenew("SA", (w + c)*frame.x + r_r*frame.z)
    steer_point.v2pt_theory(rear_centre, ground, frame)
    front_centre = steer_point.locatenew("FW", -c*fork_axes.x - r_f*fork_axes.z)
    front_centre.v2pt_theory(steer_point, ground, fork)
    fork_centre = steer_point.locatenew("HO", (x_h - w - c)*fork_axes.x + z_h*fork_axes.z)
    fork_centre.v2pt_theory(steer_point, ground, fork)
    # the front contact: the lowest point of the front wheel's rim
    axle_down = yawed.z.dot(fork_axes.y)
    reach = sympy.sqrt(1 - axle_down**2)
    down = (yawed.z - axle_down*fork_axes.y)/reach
    front_contact = front_centre.locatenew("CF", r_f*down)
    front_contact.v2pt_theory(front_centre, ground, front_wheel)

    kinematics = [q.diff() - u for q, u in zip((q3, q4, q5, q6, q7, q8), speeds)]
    bodies = [
        RigidBody("R", rear_centre, rear_wheel, m_r,
                  (inertia(frame, i_rxx, i_ryy, i_rxx), rear_centre)),
        RigidBody("B", frame_centre, frame, m_b,
                  (inertia(frame, i_bxx, i_byy, i_bzz, 0, 0, i_bxz), frame_centre)),
        RigidBody("H", fork_centre, fork, m_h,
                  (inertia(fork_axes, i_hxx, i_hyy, i_hzz, 0, 0, i_hxz), fork_centre)),
        RigidBody("F", front_centre, front_wheel, m_f,
                  (inertia(fork_axes, i_fxx, i_fyy, i_fxx), front_centre)),
    ]
    loads = [(rear_centre, m_r*g*ground.z), (frame_centre, m_b*g*ground.z),
             (fork_centre, m_h*g*ground.z), (front_centre, m_f*g*ground.z),
             (frame_centre, -PUSH*ground.y)]
    kane = KanesMethod(ground, q_ind=[q3, q4, q5, q6, q7, q8], u_ind=list(speeds),
                       kd_eqs=kinematics)
    kane.kanes_equations(bodies, loads)

    # structural replacement (xreplace; subs is an order of magnitude slower on these)
    plain = {q.diff(): u for q, u in zip((q3, q4, q5, q6, q7, q8), SPEEDS)}
    plain.update(zip(speeds, SPEEDS))
    plain.update(zip((q3, q4, q5, q7), COORDINATES))

    def flat(expr: sympy.Expr) -> sympy.Expr:
        expr = sympy.sympify(expr).xreplace(plain)
        if expr.atoms(AppliedUndef):
            raise ValueError("the wheels' angles are ignorable and must not appear")
        return expr

    height = flat((front_centre.pos_from(contact) + r_f*down).dot(ground.z))
    velocity = front_contact.vel(ground)
    # along the yawed frame's axes (forward, right, down): the same three conditions, free of
    # the yaw
    constraint = sympy.Matrix([[flat(velocity.dot(axis)).diff(s) for s in SPEEDS]
                               for axis in (yawed.x, yawed.y, yawed.z)])
    # d(B(q) u)/dt at fixed u: sum over the coordinates of dB/dq_j u * qdot_j
    yaw, roll, pitch, steer = COORDINATES
    coordinate_rates = {roll: SPEEDS[1], pitch: SPEEDS[2], steer: SPEEDS[4]}
    if yaw in constraint.free_symbols:
        raise ValueError("the contact conditions along the yawed axes must not hold the yaw")
    product = constraint*sympy.Matrix(SPEEDS)
    constraint_rate = sympy.Matrix([
        sum(product[i].diff(q)*rate for q, rate in coordinate_rates.items()) for i in range(3)])
    mass = kane.mass_matrix.applyfunc(flat)
    forcing = kane.forcing.applyfunc(flat)
    geometric = rear_centre.vel(ground) + r_r*rolled.ang_vel_in(ground).cross(rolled.z)
    contact_velocity = (flat(geometric.dot(ground.x)), flat(geometric.dot(ground.y)))
    kinetic = sum(body.kinetic_energy(ground) for body in bodies)
    potential = -g*sum(body.mass*body.masscenter.pos_from(contact).dot(ground.z)
                       for body in bodies)
    energy = flat(kinetic + potential)
    return ReducedBicycle(contact_height=height, contact_height_pitch=height.diff(pitch),
                          constraint=constraint, constraint_rate=constraint_rate, mass=mass,
                          forcing=forcing, contact_velocity=contact_velocity, energy=energy)
