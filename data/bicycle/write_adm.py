#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Write the ADAMS dataset of a bicycle from a table of its parameters.

    python3 data/bicycle/write_adm.py data/bicycle/benchmark.txt -o data/bicycle.adm
    python3 data/bicycle/write_adm.py data/bicycle/benchmark.txt --check data/bicycle.adm

The table (data/bicycle/benchmark.txt documents its format) holds the parameters of Meijaard,
Papadopoulos, Ruina and Schwab (2007), Table 1, in the paper's terms, the forward speed v and
the run's end time and output steps. The dataset has four parts (rear wheel R, rear frame B,
front frame H, front wheel F), three revolute joints, the rolling contact of each wheel as three
UCONs, gravity, and an upright, straight start at v. Before it writes anything the script checks
the geometry of the dataset text it made, independently of how it made it (check_geometry.py);
with --check it writes nothing and exits 1 when the file differs from what it would write.
Python 3 standard library only.

Axes and signs
--------------
The paper's axes: x forward, y to the right, z DOWN, origin at the rear contact point. ADAMS's
here: x forward, y to the LEFT, z UP (gravity along -Z), the same origin. The change is the half
turn about x, Q = diag(1, -1, -1), a proper rotation (right-handed axes stay right-handed):

- a point (x, y, z) of the paper is (x, -y, -z) here: the rear frame's centre of mass
  (x_B, 0, z_B) = (0.3, 0, -0.9) is at (0.3, 0, 0.9), 0.9 m above the ground;
- a tensor T is Q T Q here: the diagonal is unchanged, and the xy and xz entries change sign
  (one index flips), the yz entry keeps it (both flip). So the paper's xz entry I_Bxz = 2.4
  is the entry -2.4 of the tensor here;
- ADAMS's IP products are positive integrals, Ixz = integral of x z dm (docs/datasets.md),
  and a tensor's off-diagonal entry is minus that integral: IP's xz is minus the tensor's entry
  here, -(-2.4) = +2.4. The two sign changes cancel: IP's xz is the paper's I_Bxz as printed
  (2.4 for B, -0.00756 for H), and IP's xy and yz are 0 (the paper's are 0).

Every part's frame is ground's (no QG, no REULER): its markers' QP and REULER are positions and
3-1-3 angles in ground at t = 0, which is how the check reads them.

- The wheels. The rolling_disk and disk_height routines take the disk's CM marker z as its
  axle (docs/ucosub-disk.md), so a wheel's CM marker is REULER = 0, pi/2, 0, whose z axis is
  (0, -1, 0): the axle, pointing to the right (the paper's +y). Its IP is I_xx, I_xx, I_yy:
  the diameters first, the axle last. Rolling forward at v with the centre at height r needs
  the angular velocity (0, v/r, 0) in ground (the contact point then has v + omega x (0, 0, -r)
  = 0), that is -v/r about the CM marker's z (0, -1, 0): WZ = -v/r, as data/disk_height.adm.
  Each wheel's contact is its three UCONs: rolling_disk's components 1 and 2 (no slip along X
  and Y) and disk_height (Z - r sin(theta) = 0, the lowest rim point on the ground), PAR as in
  data/disk_height.adm.
- The frames' CM markers are ground's axes (REULER 0): their IP is the tensor above, whose
  principal axes rollcon finds (docs/datasets.md, products of inertia).
- The joints. ADAMS's REVOLUTE: the I and J markers' origins coincide and their z axes are the
  joint's axis. The wheel joints are at the axles, each marker turned as the wheel's CM marker
  (z = (0, -1, 0)). The steer axis is tilted back by lambda from the vertical and meets the
  ground the trail c ahead of the front contact (w, 0, 0): it is the line through (w + c, 0, 0)
  along (-sin(lambda), 0, cos(lambda)) (up and back). Its markers are at the point of that line
  nearest the front axle, with REULER = -pi/2, lambda, pi/2: z = (-sin(lambda), 0,
  cos(lambda)), x = (cos(lambda), 0, sin(lambda)).
- The start: every part moves at VX = v; the wheels spin as above; the frames do not turn.
  The benchmark bicycle is self-stable between about 4.3 and 6.0 m/s, so at 5 m/s an upright
  start stays upright.

Ids: parts 1 (ground), 2 R, 3 B, 4 H, 5 F; the markers of part p are 10 p + k (10 p its CM
marker); joints 1 (R on B), 2 (H on B), 3 (F on H); UCONs 1-3 the rear wheel, 4-6 the front.
"""

import argparse
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import check_geometry  # noqa: E402  (beside this script)

#: Every parameter of a table: name, the unit it takes, what it is.
PARAMETERS = (
    ("w", "m", "wheelbase"),
    ("c", "m", "trail"),
    ("lambda", "rad", "steer axis tilt from the vertical"),
    ("g", "m/s^2", "gravity"),
    ("v", "m/s", "forward speed"),
    ("r_R", "m", "rear wheel radius"),
    ("m_R", "kg", "rear wheel mass"),
    ("I_Rxx", "kg m^2", "rear wheel, about a diameter"),
    ("I_Ryy", "kg m^2", "rear wheel, about the axle"),
    ("x_B", "m", "rear frame centre of mass, x"),
    ("z_B", "m", "rear frame centre of mass, z (down)"),
    ("m_B", "kg", "rear frame mass"),
    ("I_Bxx", "kg m^2", "rear frame tensor, xx"),
    ("I_Byy", "kg m^2", "rear frame tensor, yy"),
    ("I_Bzz", "kg m^2", "rear frame tensor, zz"),
    ("I_Bxz", "kg m^2", "rear frame tensor, xz"),
    ("x_H", "m", "front frame centre of mass, x"),
    ("z_H", "m", "front frame centre of mass, z (down)"),
    ("m_H", "kg", "front frame mass"),
    ("I_Hxx", "kg m^2", "front frame tensor, xx"),
    ("I_Hyy", "kg m^2", "front frame tensor, yy"),
    ("I_Hzz", "kg m^2", "front frame tensor, zz"),
    ("I_Hxz", "kg m^2", "front frame tensor, xz"),
    ("r_F", "m", "front wheel radius"),
    ("m_F", "kg", "front wheel mass"),
    ("I_Fxx", "kg m^2", "front wheel, about a diameter"),
    ("I_Fyy", "kg m^2", "front wheel, about the axle"),
    ("push", "N s", "impulse of a sideways push on the rear frame (0: none)"),
    ("push_time", "s", "when the push starts"),
    ("push_length", "s", "how long the push lasts (a half-sine pulse)"),
    ("end_time", "s", "SIMULATE END"),
    ("steps", "1", "SIMULATE STEPS"),
)

#: Where this script lives in the repository: data/bicycle/
REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


class TableError(Exception):
    """A table that cannot be read: the message names the file and line."""


def file_problem(path, error, writing=False):
    """What went wrong with the file at path, in words that name it (never a traceback)."""
    if isinstance(error, UnicodeDecodeError):
        line = error.object[:error.start].count(b"\n") + 1
        return (f"{path}:{line}: not ASCII text (byte 0x{error.object[error.start]:02x} at "
                f"offset {error.start})")
    if isinstance(error, IsADirectoryError):
        return f"{path}: is a folder, not a file"
    if isinstance(error, FileNotFoundError):
        folder = pathlib.Path(path).parent
        if writing and not folder.is_dir():
            return f"{path}: cannot write: no folder {folder}"
        return f"{path}: no such file"
    if isinstance(error, NotADirectoryError):
        return f"{path}: a part of the path is not a folder"
    if isinstance(error, PermissionError):
        return f"{path}: permission denied" + (" (cannot write)" if writing else "")
    return f"{path}: {error.strerror or error}"


def read_table(path):
    """The table at path as {name: value in SI}; every parameter once, none unknown."""
    units = {name: unit for name, unit, _ in PARAMETERS}
    values = {}
    text = pathlib.Path(path).read_text(encoding="ascii")
    for number, line in enumerate(text.splitlines(), start=1):
        where = f"{path}:{number}"
        fields = line.split("#", 1)[0].split()
        if not fields:
            continue
        if len(fields) < 3:
            raise TableError(f"{where}: expected 'name value unit', got '{line.strip()}'")
        name, written, unit = fields[0], fields[1], " ".join(fields[2:])
        if name not in units:
            raise TableError(f"{where}: '{name}' is not a parameter (expected one of "
                             + ", ".join(units) + ")")
        if name in values:
            raise TableError(f"{where}: {name} is given twice")
        try:
            value = float(written)
        except ValueError:
            raise TableError(f"{where}: {name}: '{written}' is not a number") from None
        if not math.isfinite(value):
            raise TableError(f"{where}: {name}: '{written}' is not a finite number")
        if name == "lambda" and unit == "deg":
            value, unit = math.radians(value), "rad"
        if unit != units[name]:
            raise TableError(f"{where}: {name} is in {units[name]}"
                             + (" or deg" if name == "lambda" else "") + f", got '{unit}'")
        values[name] = value
    missing = [name for name in units if name not in values]
    if missing:
        raise TableError(f"{path}: missing " + ", ".join(missing))
    positive = ("w", "g", "r_R", "m_R", "I_Rxx", "I_Ryy", "m_B", "m_H", "r_F", "m_F", "I_Fxx",
                "I_Fyy", "push_length", "end_time", "steps")
    for name in positive:
        if not values[name] > 0:
            raise TableError(f"{path}: {name} must be > 0 [{units[name]}], got {values[name]}")
    if values["steps"] != int(values["steps"]):
        raise TableError(f"{path}: steps must be a whole number, got {values['steps']}")
    if not 0 <= values["lambda"] < math.pi / 2:
        raise TableError(f"{path}: lambda must be >= 0 and < pi/2 [rad], got {values['lambda']}")
    return values


def number(value):
    """A value as the dataset writes it: the shortest text that reads back to the same double."""
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    return repr(value)


def numbers(*values):
    return ", ".join(number(v) for v in values)


def steer_point(p):
    """The point of the steer axis nearest the front axle, in ground (z up) [m]."""
    axis = (-math.sin(p["lambda"]), 0.0, math.cos(p["lambda"]))
    ground_point = (p["w"] + p["c"], 0.0, 0.0)
    axle = (p["w"], 0.0, p["r_F"])
    s = sum((a - b) * u for a, b, u in zip(axle, ground_point, axis))
    return tuple(b + s * u for b, u in zip(ground_point, axis))


def display_path(path):
    """path relative to the repository when it is inside it (the header then does not depend
    on where the script was run from), else as given."""
    try:
        return str(pathlib.Path(path).resolve().relative_to(REPOSITORY))
    except ValueError:
        return str(path)


def dataset_text(p, table_path, out_path):
    """The dataset of the bicycle of table p (module docstring), as text."""
    wheel_axle = numbers(0, math.pi / 2, 0)
    steer = numbers(-math.pi / 2, p["lambda"], math.pi / 2)
    s = steer_point(p)
    rear_axle = numbers(0, 0, p["r_R"])
    front_axle = numbers(p["w"], 0, p["r_F"])
    v = p["v"]
    command = (f"python3 data/bicycle/write_adm.py {display_path(table_path)} "
               f"-o {display_path(out_path)}")
    lines = [
        "bicycle: the benchmark bicycle of Meijaard et al. (2007), upright and straight at "
        + number(v) + " m/s",
        f"! Written by {command}",
        f"! from the table {display_path(table_path)}: do not edit; change the table and run "
        "that again.",
        "! The docstring of data/bicycle/write_adm.py explains every number and sign: the",
        "! paper's axes (x forward, y right, z down) become ADAMS's (x forward, y left, z up);",
        "! every part's frame is ground's, so QP and REULER are in ground at t = 0.",
        "UNITS/SYSTEM=SI",
        "",
        "PART/1, GROUND",
        "",
        "! Rear wheel R: its CM marker's z is the axle (to the right), IP about it last.",
        f"PART/2, MASS={number(p['m_R'])}, CM=20, "
        f"IP={numbers(p['I_Rxx'], p['I_Rxx'], p['I_Ryy'])}",
        f", VX={number(v)}, WZ={number(-v / p['r_R'])}",
        f"MARKER/20, PART=2, QP={rear_axle}, REULER={wheel_axle}",
        f"MARKER/21, PART=2, QP={rear_axle}, REULER={wheel_axle}    ! joint 1, I",
        "",
        "! Rear frame and rider B: IP with the product xz (ADAMS's integral, module docstring).",
        f"PART/3, MASS={number(p['m_B'])}, CM=30",
        f", IP={numbers(p['I_Bxx'], p['I_Byy'], p['I_Bzz'], 0, p['I_Bxz'], 0)}",
        f", VX={number(v)}",
        f"MARKER/30, PART=3, QP={numbers(p['x_B'], 0, -p['z_B'])}",
        f"MARKER/31, PART=3, QP={rear_axle}, REULER={wheel_axle}    ! joint 1, J",
        f"MARKER/32, PART=3, QP={numbers(*s)}, REULER={steer}    ! joint 2, J",
        "",
        "! Front frame H (handlebar and fork), turning about the steer axis.",
        f"PART/4, MASS={number(p['m_H'])}, CM=40",
        f", IP={numbers(p['I_Hxx'], p['I_Hyy'], p['I_Hzz'], 0, p['I_Hxz'], 0)}",
        f", VX={number(v)}",
        f"MARKER/40, PART=4, QP={numbers(p['x_H'], 0, -p['z_H'])}",
        f"MARKER/41, PART=4, QP={numbers(*s)}, REULER={steer}    ! joint 2, I",
        f"MARKER/42, PART=4, QP={front_axle}, REULER={wheel_axle}    ! joint 3, J",
        "",
        "! Front wheel F.",
        f"PART/5, MASS={number(p['m_F'])}, CM=50, "
        f"IP={numbers(p['I_Fxx'], p['I_Fxx'], p['I_Fyy'])}",
        f", VX={number(v)}, WZ={number(-v / p['r_F'])}",
        f"MARKER/50, PART=5, QP={front_axle}, REULER={wheel_axle}",
        f"MARKER/51, PART=5, QP={front_axle}, REULER={wheel_axle}    ! joint 3, I",
        "",
        "! The joints: each pair of markers at one point, their z axes the joint's axis.",
        "JOINT/1, REVOLUTE, I=21, J=31    ! rear wheel on the rear frame, at the rear axle",
        "JOINT/2, REVOLUTE, I=41, J=32    ! front frame on the rear frame, the steer axis",
        "JOINT/3, REVOLUTE, I=51, J=42    ! front wheel on the front frame, at the front axle",
        "",
        "! Each wheel rolls without slip (rolling_disk's components 1 and 2) with its lowest rim",
        "! point on the ground (disk_height), as data/disk_height.adm; PAR(10) and PAR(4): r [m].",
    ]
    for first, part, radius in ((1, 2, p["r_R"]), (4, 5, p["r_F"])):
        codes = f"{part}, 21, 22, 23, 14, 15, 24, 25, 26, {number(radius)}"
        lines += [
            f"UCON/{first}, FUNCTION=USER({codes}, 1), ROUTINE=rolling_disk",
            f"UCON/{first + 1}, FUNCTION=USER({codes}, 2), ROUTINE=rolling_disk",
            f"UCON/{first + 2}, FUNCTION=USER({part}, 13, 15, {number(radius)}), "
            "ROUTINE=disk_height",
        ]
    t0, length, impulse = p["push_time"], p["push_length"], p["push"]
    t1 = t0 + length
    peak = math.pi / 2 * impulse / length
    pulse = f"{number(peak)}*SIN(PI*(TIME - {number(t0)})/{number(length)})"
    lines += [
        "",
        f"! A push sideways (+Y, to the left) on the rear frame at its centre of mass: a half-sine",
        f"! pulse from t = {number(t0)} s lasting {number(length)} s carrying {number(impulse)} N s"
        " (peak pi J / (2 T) [N]),",
        "! zero at t = 0, so the start is the steady upright motion that rollcon linear",
        "! linearises. Markers 1 (the force's axes, RM) and 2 (its reaction, JFLOAT) are ground's.",
        "MARKER/1, PART=1",
        "MARKER/2, PART=1",
        "GFORCE/1, I=30, JFLOAT=2, RM=1, FX=0, FZ=0, TX=0, TY=0, TZ=0",
        f", FY=IF(TIME - {number(t0)}: 0, 0, IF(TIME - {number(t1)}: {pulse}, {pulse}, 0))",
    ]
    lines += [
        "",
        "! Gravity along -Z [m/s^2].",
        f"ACCGRAV/KGRAV={number(-p['g'])}",
        "",
        f"SIMULATE/DYNAMIC, END={number(p['end_time'])}, STEPS={number(p['steps'])}",
        "INTEGRATOR/FORMULATION=IDA, ERROR=1E-10",
        "",
        "END",
    ]
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description="Write the ADAMS dataset of a bicycle from a "
                                     "table of its parameters (the benchmark's terms).")
    parser.add_argument("table", help="the parameter table (data/bicycle/benchmark.txt)")
    target = parser.add_mutually_exclusive_group(required=True)
    target.add_argument("-o", "--output", help="the dataset to write (data/bicycle.adm)")
    target.add_argument("--check", metavar="ADM",
                        help="write nothing; exit 1 when ADM is not what would be written")
    args = parser.parse_args(argv)
    try:
        table = read_table(args.table)
    except TableError as error:
        print(f"write_adm.py: {error}", file=sys.stderr)
        return 2
    except (OSError, UnicodeDecodeError) as error:
        print(f"write_adm.py: {file_problem(args.table, error)}", file=sys.stderr)
        return 2
    out = args.output or args.check
    text = dataset_text(table, args.table, out)
    problems = check_geometry.check(table, text)
    if problems:
        print("write_adm.py: the dataset's geometry is wrong:\n  " + "\n  ".join(problems),
              file=sys.stderr)
        return 2
    if args.check:
        try:
            current = pathlib.Path(args.check).read_text(encoding="ascii")
        except (OSError, UnicodeDecodeError) as error:
            print(f"write_adm.py: {file_problem(args.check, error)}", file=sys.stderr)
            return 1
        if current != text:
            print(f"write_adm.py: {args.check} is not what {args.table} gives; regenerate "
                  f"with: python3 data/bicycle/write_adm.py {args.table} -o {args.check}",
                  file=sys.stderr)
            return 1
        return 0
    try:
        pathlib.Path(args.output).write_text(text, encoding="ascii")
    except OSError as error:
        print(f"write_adm.py: {file_problem(args.output, error, writing=True)}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
