#!/usr/bin/env python3
"""Read a CalculiX run of a deck from `hertz_3d_inp.py` and print the Hertz measures of
`hertz_ref.py` (those of tests/hertz_sphere_3d.rs): F, a, p0 and their errors.

  read_ccx.py JOB            (reads JOB.inp, JOB.dat, JOB.sta and, if present, JOB.log)

Per slave node in contact (pressure > 0 in CSTR at the last time): N = p * (its spring area,
CalculiX's: a quarter of each slave face around it, in the current configuration), its
current position = node + U. p0 = N / A over the reference tributary area, as contrail's test
divides by its (reference) area. Also printed: the total reaction on the cap's nodes (the z
force on the sphere, a check on sum(N)), the number of equations and Newton iterations.
Exits non-zero when the run did not reach the end of the step or a number is missing.
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hertz_ref import measure, report, tributary_areas  # noqa: E402


def fail(msg):
    print(f"read_ccx: {msg}", file=sys.stderr)
    sys.exit(1)


def read_inp(path):
    nodes, elements, elsets, surfaces = {}, {}, {}, {}
    mode, name = None, None
    for raw in open(path):
        s = raw.strip()
        if not s or s.startswith("**"):
            continue
        if s.startswith("*"):
            key = s.split(",")[0].upper()
            params = {p.split("=")[0].strip().upper(): p.split("=")[1].strip() for p in s.split(",")[1:] if "=" in p}
            mode, name = key, params.get("ELSET") or params.get("NAME")
            if key == "*ELEMENT" and name:
                elsets.setdefault(name, [])
            continue
        f = [t.strip() for t in s.split(",") if t.strip()]
        if mode == "*NODE":
            nodes[int(f[0])] = tuple(float(v) for v in f[1:4])
        elif mode == "*ELEMENT":
            elements[int(f[0])] = [int(v) for v in f[1:]]
            if name:
                elsets[name].append(int(f[0]))
        elif mode == "*ELSET":
            elsets.setdefault(name, []).extend(int(v) for v in f)
        elif mode == "*SURFACE":
            surfaces.setdefault(name.upper(), []).append((f[0], f[1].upper()))
    return nodes, elements, elsets, surfaces


# C3D8 faces (CalculiX numbering, 1-based node positions), each counter-clockwise from outside
FACES = {"S1": (1, 4, 3, 2), "S2": (5, 6, 7, 8), "S3": (1, 2, 6, 5), "S4": (2, 3, 7, 6), "S5": (3, 4, 8, 7), "S6": (4, 1, 5, 8)}


def slave_quads(elements, elsets, surfaces):
    quads = []
    for elset, face in surfaces.get("SLAVE", []):
        for e in elsets[elset]:
            quads.append([elements[e][i - 1] for i in FACES[face]])
    if not quads:
        fail("no slave surface in the deck")
    return quads


def last_blocks(path):
    """The .dat's blocks at its last time: {title: [rows of floats]}."""
    blocks, title, last_time = {}, None, None
    for raw in open(path):
        s = raw.strip()
        m = re.match(r"(.*) and time\s+(\S+)$", s)
        if m:
            title, t = m.group(1), float(m.group(2))
            if last_time is None or t > last_time + 1e-12:
                blocks, last_time = {}, t
            blocks[title] = []
            continue
        if s and title is not None:
            blocks[title].append([float(v) for v in s.split()])
    return last_time, blocks


def find(blocks, prefix):
    for k, v in blocks.items():
        if k.startswith(prefix):
            return v
    fail(f"no block '{prefix}' at the last time in the .dat")


def main():
    if len(sys.argv) != 2:
        fail("usage: read_ccx.py JOB")
    job = sys.argv[1]
    nodes, elements, elsets, surfaces = read_inp(job + ".inp")
    quads = slave_quads(elements, elsets, surfaces)
    time, blocks = last_blocks(job + ".dat")
    if time is None or abs(time - 1.0) > 1e-9:
        fail(f"the .dat ends at time {time}, not at the end of the step (1.0)")
    rf = find(blocks, "total force (fx,fy,fz) for set NCAP")
    u = {int(r[0]): r[1:4] for r in find(blocks, "displacements (vx,vy,vz) for set NTOP")}
    cstr = {int(r[0]): r[1] for r in find(blocks, "contact stress (slave node,press,tang1,tang2)")}
    ref = tributary_areas(nodes, quads)
    cur_xyz = {n: tuple(nodes[n][c] + u[n][c] for c in range(3)) for n in ref if n in u}
    if len(cur_xyz) != len(ref):
        fail("displacements missing for some slave nodes")
    cur = tributary_areas(cur_xyz, quads)
    points = []
    for n, p in cstr.items():
        if p > 0.0:
            x = cur_xyz[n]
            points.append((x[0], x[1], p * cur[n], ref[n]))
    m = measure(points)
    # the sta: every increment's Newton iterations; the last line must reach the step's end
    iters, tot = 0, None
    for raw in open(job + ".sta"):
        f = raw.split()
        if len(f) == 7 and f[0].isdigit():
            iters += int(f[3])
            tot = float(f[4])
    if tot is None or abs(tot - 1.0) > 1e-9:
        fail(f"the .sta ends at total time {tot}")
    extra = {}
    if os.path.exists(job + ".log"):
        log = open(job + ".log").read()
        if "Job finished" not in log:
            fail("no 'Job finished' in the log")
        eq = re.findall(r"number of equations\s+(\d+)", log)
        if eq:
            extra["unknowns"] = eq[-1]
    extra["iterations"] = iters
    extra["F_reaction"] = f"{-4.0 * rf[0][2]:.7g}"
    report("ccx", job, m, extra, note=f"reaction on the cap {-4.0 * rf[0][2]:.6f}; ")

if __name__ == "__main__":
    main()
