#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Check a bicycle dataset's geometry against its parameter table, from the dataset's text.

    python3 data/bicycle/check_geometry.py data/bicycle/benchmark.txt data/bicycle.adm

This reads the statements back (PART, MARKER, JOINT, UCON, ACCGRAV, SIMULATE), places every
marker in ground by its part's QG and REULER and its own QP and REULER (3-1-3 angles, composed
here from the three elementary turns), and checks what the paper's bicycle must be, in ground
axes x forward, y left, z up (write_adm.py's docstring):

- every JOINT's I and J markers are on two parts, at one point, with one z axis;
- each wheel (a part with rolling_disk and disk_height UCONs) has its CM marker's z along a
  horizontal axle, its centre one radius above the ground, its lowest point on the ground, a
  joint at its axle about that axle; the rear contact at the origin, the front one at x = w;
- the other joint is the steer axis: tilted back by lambda from the vertical, meeting the ground
  the trail c ahead of the front contact;
- the masses, the centres of mass (the paper's z is down), and every inertia tensor turned back
  into the paper's axes (products from ADAMS's positive integrals) are the table's;
- every part starts at v along x, each wheel's contact point at rest (rolling), the frames not
  turning; gravity and the run as the table says.

write_adm.py runs it on what it is about to write; the test suite adm-bicycle runs it on
data/bicycle.adm. Python 3 standard library only.
"""

import math
import pathlib
import sys

#: Lengths are checked to this [m] and directions to this: the dataset writes its numbers to
#: full precision (repr), so what it holds is exact to a few 1e-16
TOLERANCE = 1e-12


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(m, v):
    return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]


def transpose(m):
    return [[m[j][i] for j in range(3)] for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def turn_z(angle):
    c, s = math.cos(angle), math.sin(angle)
    return [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]


def turn_x(angle):
    c, s = math.cos(angle), math.sin(angle)
    return [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]


def euler_313(angles):
    """ADAMS's body-fixed 3-1-3 turn: about z by psi, the new x by theta, the new z by phi."""
    psi, theta, phi = angles
    return matmul(matmul(turn_z(psi), turn_x(theta)), turn_z(phi))


def read_number(text):
    """A dataset number; a trailing D means degrees."""
    text = text.strip()
    if text[-1:] in "dD" and len(text) > 1:
        return math.radians(float(text[:-1]))
    return float(text.replace("D", "E").replace("d", "e"))


def split_top(text):
    """Fields separated by commas outside parentheses."""
    fields, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        elif ch == "," and depth == 0:
            fields.append(text[start:i])
            start = i + 1
    fields.append(text[start:])
    return [f.strip() for f in fields if f.strip()]


def statements(text):
    """(name, id, {KEY: [values]}) for every statement after the title, up to END."""
    joined = []
    for line in text.splitlines()[1:]:
        line = line.split("!", 1)[0].rstrip()
        if not line.strip():
            continue
        if line.lstrip().startswith(",") and joined:
            joined[-1] += line
        else:
            joined.append(line)
    found = []
    for line in joined:
        head, _, rest = line.partition(",")
        name, _, ident = head.strip().partition("/")
        name = name.upper()
        if name == "END":
            break
        keys, last = {}, None
        fields = split_top(rest)
        if ident and "=" in ident:  # NAME/KEY=value (no id)
            fields.insert(0, ident)
            ident = ""
        elif ident and not ident.strip().isdigit():  # NAME/WORD
            keys[ident.strip().upper()] = []
            ident = ""
        for field in fields:
            if "=" in field:
                key, _, value = field.partition("=")
                last = key.strip().upper()
                keys[last] = [value.strip()]
            elif last is not None and _is_number(field):
                keys[last].append(field)
            else:
                keys[field.upper()] = []
                last = None
        found.append((name, int(ident) if ident else None, keys))
    return found


def _is_number(text):
    try:
        read_number(text)
        return True
    except ValueError:
        return False


def numbers_of(keys, key, default):
    return [read_number(v) for v in keys[key]] if key in keys else list(default)


def check(table, text):
    """The problems found in the dataset text (an empty list: none), against table (SI)."""
    problems = []

    def expect(condition, message):
        if not condition:
            problems.append(message)

    def near(a, b, tolerance=TOLERANCE):
        return abs(a - b) <= tolerance * max(1.0, abs(b))

    parts, markers, joints, ucons, other = {}, {}, {}, {}, {}
    for name, ident, keys in statements(text):
        if name == "PART":
            parts[ident] = keys
        elif name == "MARKER":
            markers[ident] = keys
        elif name == "JOINT":
            joints[ident] = keys
        elif name == "UCON":
            ucons[ident] = keys
        else:
            other[name] = keys

    def part_pose(p):
        keys = parts[p]
        return numbers_of(keys, "QG", [0, 0, 0]), euler_313(numbers_of(keys, "REULER", [0, 0, 0]))

    def marker_pose(m):
        keys = markers[m]
        p = int(keys["PART"][0])
        origin, turn = part_pose(p)
        point = [o + d for o, d in zip(origin, apply(turn, numbers_of(keys, "QP", [0, 0, 0])))]
        axes = matmul(turn, euler_313(numbers_of(keys, "REULER", [0, 0, 0])))
        return p, point, axes

    def z_axis(axes):
        return [axes[0][2], axes[1][2], axes[2][2]]

    grounds = [p for p, keys in parts.items() if "GROUND" in keys]
    expect(len(grounds) == 1, f"{len(grounds)} ground parts, expected 1")
    bodies = [p for p in parts if p not in grounds]
    expect(len(bodies) == 4, f"{len(bodies)} parts besides ground, expected 4")

    # the joints: one point, one axis
    joint_parts = {}
    for j, keys in joints.items():
        expect("REVOLUTE" in keys, f"JOINT/{j} is not REVOLUTE")
        pi, point_i, axes_i = marker_pose(int(keys["I"][0]))
        pj, point_j, axes_j = marker_pose(int(keys["J"][0]))
        expect(pi != pj, f"JOINT/{j}: I and J on one part")
        distance = math.dist(point_i, point_j)
        expect(distance <= TOLERANCE, f"JOINT/{j}: I and J are {distance} m apart")
        alignment = sum(a * b for a, b in zip(z_axis(axes_i), z_axis(axes_j)))
        expect(near(alignment, 1.0), f"JOINT/{j}: the z axes of I and J differ (cos {alignment})")
        joint_parts[j] = (pi, pj, point_i, z_axis(axes_i))
    expect(len(joints) == 3, f"{len(joints)} joints, expected 3")

    # the wheels: parts with rolling contact UCONs
    wheels = {}
    for u, keys in ucons.items():
        routine = keys.get("ROUTINE", [""])[0].lower()
        par = [read_number(v) for v in split_top(keys["FUNCTION"][0].strip()[5:-1])]
        p = int(par[0])
        entry = wheels.setdefault(p, {"components": set(), "radii": set()})
        if routine == "rolling_disk":
            entry["components"].add(int(par[10]))
            entry["radii"].add(par[9])
            expect(par[1:9] == [21, 22, 23, 14, 15, 24, 25, 26],
                   f"UCON/{u}: rolling_disk codes {par[1:9]}")
        elif routine == "disk_height":
            entry["components"].add("height")
            entry["radii"].add(par[3])
            expect(par[1:3] == [13, 15], f"UCON/{u}: disk_height codes {par[1:3]}")
        else:
            problems.append(f"UCON/{u}: routine '{routine}'")
    expect(len(wheels) == 2, f"{len(wheels)} wheels with rolling contact, expected 2")
    if len(wheels) != 2 or len(joints) != 3 or problems:
        return problems

    v = table["v"]
    centres = {}
    for p, entry in wheels.items():
        expect(entry["components"] == {1, 2, "height"},
               f"PART/{p}: the wheel's UCONs are {entry['components']}")
        expect(len(entry["radii"]) == 1, f"PART/{p}: its UCONs disagree on the radius")
        radius = entry["radii"].pop()
        cm = int(parts[p]["CM"][0])
        _, centre, axes = marker_pose(cm)
        axle = z_axis(axes)
        expect(abs(axle[2]) <= TOLERANCE, f"PART/{p}: the axle (CM marker z) is not horizontal")
        expect(near(centre[2], radius), f"PART/{p}: the centre is {centre[2]} m high, radius "
               f"{radius} m")
        # the lowest rim point: from the centre, down in the wheel's plane
        down = cross(axle, cross([0.0, 0.0, -1.0], axle))
        contact = [c + radius * d for c, d in zip(centre, down)]
        expect(abs(contact[2]) <= TOLERANCE, f"PART/{p}: the contact is {contact[2]} m high")
        on_axle = [j for j, (pi, pj, point, axis) in joint_parts.items() if p in (pi, pj)
                   and math.dist(point, centre) <= TOLERANCE
                   and near(abs(sum(a * b for a, b in zip(axis, axle))), 1.0)]
        expect(len(on_axle) == 1, f"PART/{p}: no joint about its axle at its centre")
        centres[p] = (centre, contact, radius, axes)
        # rolling: the contact point at rest, the centre at v along x
        velocity = [numbers_of(parts[p], k, [0])[0] for k in ("VX", "VY", "VZ")]
        expect(velocity == [v, 0, 0], f"PART/{p}: velocity {velocity}, expected ({v}, 0, 0)")
        omega = apply(axes, [numbers_of(parts[p], k, [0])[0] for k in ("WX", "WY", "WZ")])
        slip = [a + b for a, b in zip(velocity, cross(omega, [c - x for c, x in
                                                               zip(contact, centre)]))]
        expect(max(map(abs, slip)) <= TOLERANCE * v, f"PART/{p}: the contact slips at {slip}")
    rear, front = sorted(centres, key=lambda p: centres[p][0][0])
    expect(math.dist(centres[rear][1], [0, 0, 0]) <= TOLERANCE,
           f"the rear contact is at {centres[rear][1]}, not the origin")
    expect(math.dist(centres[front][1], [table["w"], 0, 0]) <= TOLERANCE,
           f"the front contact is at {centres[front][1]}, not (w, 0, 0)")
    expect(near(centres[rear][2], table["r_R"]) and near(centres[front][2], table["r_F"]),
           "the wheels' radii are not r_R and r_F")

    # the steer axis: the joint of two frames
    frames = [p for p in bodies if p not in wheels]
    steer = [j for j, (pi, pj, _, _) in joint_parts.items() if {pi, pj} == set(frames)]
    expect(len(steer) == 1, "no joint between the two frames")
    if problems:
        return problems
    _, _, point, axis = joint_parts[steer[0]]
    if axis[2] < 0:
        axis = [-a for a in axis]
    tilt = math.acos(max(-1.0, min(1.0, axis[2])))
    expect(near(tilt, table["lambda"]), f"the steer axis is tilted {tilt} rad from the vertical, "
           f"lambda is {table['lambda']}")
    expect(axis[0] <= 0 and abs(axis[1]) <= TOLERANCE, "the steer axis does not lean back in "
           "the bicycle's plane")
    ground = [q - point[2] / axis[2] * a for q, a in zip(point, axis)]
    expect(near(ground[0] - table["w"], table["c"]) and abs(ground[1]) <= TOLERANCE,
           f"the steer axis meets the ground at {ground}: trail {ground[0] - table['w']} m, "
           f"c is {table['c']} m")

    # masses, centres of mass and inertia tensors, turned back into the paper's axes
    flip = [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]]
    def holding(wheel):
        return [p for p in frames if any({p, wheel} == {pi, pj}
                                         for pi, pj, _, _ in joint_parts.values())]

    expect(len(holding(front)) == 1 and len(holding(rear)) == 1
           and holding(front) != holding(rear), "each wheel is not held by its own frame")
    if problems:
        return problems
    body_of = {rear: "R", front: "F", holding(front)[0]: "H", holding(rear)[0]: "B"}
    for p, body in body_of.items():
        keys = parts[p]
        expect(near(read_number(keys["MASS"][0]), table[f"m_{body}"]), f"PART/{p}: mass")
        ip = [read_number(x) for x in keys["IP"]] + [0.0] * (6 - len(keys["IP"]))
        xx, yy, zz, xy, xz, yz = ip
        tensor = [[xx, -xy, -xz], [-xy, yy, -yz], [-xz, -yz, zz]]
        _, centre, axes = marker_pose(int(keys["CM"][0]))
        paper = matmul(matmul(flip, matmul(matmul(axes, tensor), transpose(axes))), flip)
        if body in "RF":
            lateral = table[f"I_{body}yy"]
            expected = [[table[f"I_{body}xx"], 0, 0], [0, lateral, 0], [0, 0, table[f"I_{body}xx"]]]
        else:
            expected = [[table[f"I_{body}xx"], 0, table[f"I_{body}xz"]],
                        [0, table[f"I_{body}yy"], 0],
                        [table[f"I_{body}xz"], 0, table[f"I_{body}zz"]]]
            paper_centre = apply(flip, centre)
            expect(math.dist(paper_centre, [table[f"x_{body}"], 0, table[f"z_{body}"]])
                   <= TOLERANCE, f"PART/{p} ({body}): the centre of mass is {paper_centre} in "
                   "the paper's axes")
            velocity = [numbers_of(keys, k, [0])[0] for k in ("VX", "VY", "VZ", "WX", "WY", "WZ")]
            expect(velocity == [v, 0, 0, 0, 0, 0], f"PART/{p} ({body}): start {velocity}")
        worst = max(abs(paper[i][k] - expected[i][k]) for i in range(3) for k in range(3))
        expect(worst <= TOLERANCE, f"PART/{p} ({body}): its inertia tensor in the paper's axes "
               f"is {paper}, expected {expected}")

    gravity = numbers_of(other.get("ACCGRAV", {}), "KGRAV", [0])[0]
    expect(near(gravity, -table["g"]), f"gravity {gravity} m/s^2 along Z, expected -g")
    run = other.get("SIMULATE", {})
    expect("DYNAMIC" in run and near(numbers_of(run, "END", [0])[0], table["end_time"])
           and numbers_of(run, "STEPS", [0])[0] == table["steps"], "SIMULATE is not the table's")
    return problems


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2:
        print("usage: check_geometry.py TABLE DATASET", file=sys.stderr)
        return 2
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    import write_adm  # noqa: E402  (the table's reader, beside this script)
    try:
        table = write_adm.read_table(argv[0])
        text = pathlib.Path(argv[1]).read_text(encoding="ascii")
    except (OSError, UnicodeDecodeError, write_adm.TableError) as error:
        print(f"check_geometry.py: {error}", file=sys.stderr)
        return 2
    problems = check(table, text)
    if problems:
        print(f"check_geometry.py: {argv[1]}:\n  " + "\n  ".join(problems), file=sys.stderr)
        return 1
    print(f"{argv[1]}: joints, wheels, contacts, trail, tilt, inertias and start as "
          f"{argv[0]} says")
    return 0


if __name__ == "__main__":
    sys.exit(main())
