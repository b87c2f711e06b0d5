"""A disk rolling without slip on a plane tilted by alpha about ground X (rollcon test data).

The plane's unit normal is m = (0, -sin alpha, cos alpha); its two in-plane directions are
ground X and the line of steepest ascent s = (0, cos alpha, sin alpha). The disk's axle is its
body z axis k (3-1-3 angles psi, theta). The point of the rim nearest the plane lies from the
centre along -R c, c = k x (m x k) / |m x k|: m with its component along the axle removed,
made unit. The material point there has velocity (xdot, ydot, zdot) + w x (-R c), w the disk's
angular velocity from the 3-1-3 rates; no slip and no penetration hold its three components
along X, s and m at zero. |m x k| is zero when the disk lies flat on the plane: the spec's
singularity, near which the entries bend sharply.

Regenerate its routine (test/incline/incline_roll_ucosub.f) from the checkout:
    python3 -m ucon write test/incline/incline_roll_spec.py --out test/incline
"""
import sympy
from sympy import cos, sin
from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

vx, vy, vz = sympy.symbols("xdot ydot zdot", real=True)
psi, theta = sympy.symbols("psi theta", real=True)
psi_rate, theta_rate, phi_rate = sympy.symbols("psidot thetadot phidot", real=True)
radius = sympy.Symbol("radius", positive=True)
tilt = sympy.Symbol("alpha", real=True)

ground_z = sympy.Matrix([0, 0, 1])
line_of_nodes = sympy.Matrix([cos(psi), sin(psi), 0])
axle = sympy.Matrix([sin(psi) * sin(theta), -cos(psi) * sin(theta), cos(theta)])
normal = sympy.Matrix([0, -sin(tilt), cos(tilt)])
across = sympy.Matrix([1, 0, 0])
uphill = sympy.Matrix([0, cos(tilt), sin(tilt)])

towards_plane = axle.cross(normal.cross(axle))
to_contact = towards_plane / sympy.sqrt(1 - normal.dot(axle) ** 2)
spin = psi_rate * ground_z + theta_rate * line_of_nodes + phi_rate * axle
contact_velocity = sympy.Matrix([vx, vy, vz]) + spin.cross(-radius * to_contact)

SPEC = ConstraintSpec(
    name="incline_roll",
    title="disk rolling on an incline",
    summary="A disk rolling without slip or penetration on a plane tilted by alpha about X.",
    variables=(Variable(vx, 21), Variable(vy, 22), Variable(vz, 23),
               Variable(psi, 14), Variable(theta, 15),
               Variable(psi_rate, 24), Variable(theta_rate, 25), Variable(phi_rate, 26)),
    parameters=(Parameter(radius, 10, "disk radius R", "m", check="positive"),
                Parameter(tilt, 11, "tilt alpha of the plane about ground X", "rad",
                          check="finite")),
    constraints=tuple(
        Constraint(sympy.expand(contact_velocity.dot(direction)),
                   f"velocity of the rim's contact point along {words} [m/s]")
        for direction, words in ((across, "ground X"), (uphill, "the incline's uphill line"),
                                 (normal, "the incline's normal"))),
    component_meaning="component (1 along X, 2 uphill, 3 along the normal)",
    simplify=False,
)
