#!/usr/bin/env python3
"""Write a CalculiX (ccx 2.20) input deck of contrail's built-in `hertz-3d` scene.

The same model as `scenes/hertz-3d.toml`, at a given mesh:

* Block 1 x 1 x 1 below z = 0 (origin (0, 0, -1)), hexahedra `NX x NY x NZ` with contrail's
  box-mesh grading (`src/model/mesh.rs::graded_coords`: per axis, element sizes in geometric
  progression, the last over the first = the grading; [16, 16, 1/16]: fine at x = 0, y = 0 and
  at the top z = 0). Nodes are numbered as contrail numbers them (x fastest, then y, then z),
  plus one, so the coordinates coincide node by node.
* Element C3D8I: CalculiX's incompatible-modes hexahedron (Taylor, Beresford & Wilson's
  bubbles, 3 extra nodes = 9 extra unknowns per element), its counterpart of contrail's
  EAS hexahedron. Not the same element: both remove shear locking and most volumetric
  locking, by different enhanced fields.
* Material: *HYPERELASTIC, NEO HOOKE, U = C10 (I1bar - 3) + (J - 1)^2 / D1 with C10 = mu/2 and
  D1 = 2/K (mu = E/(2(1+nu)), K = E/(3(1-2nu))): the same small-strain moduli as contrail's
  neo-Hooke W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2 (a different compressible
  extension: the two differ at second order in the strain).
* Supports as in contrail: z = 0 on z = -1, x = 0 on x = 0, y = 0 on y = 0; NLGEOM.
* The rigid sphere (R = 1, centre (0, 0, 1)): CalculiX has no analytical rigid surface, so it
  is a quarter spherical cap of C3D8R elements (one layer, R - t .. R) whose every node is
  prescribed the sphere's motion (u = (0, 0, -0.005) ramped over the step): a rigid body in
  pure translation, exactly what contrail prescribes (a *RIGID BODY with a reference node
  would be the same constraint for a translation, with more equations). Its contact face (the
  outer face, radius R) is the master surface. The cap's elements only carry that face: all
  their nodes are prescribed, so their stiffness never enters the solution (C3D8R: the
  cheapest to evaluate; C3D8 gives the same numbers, about 30 % slower on 8x8x6). Its nodes lie on the sphere, in plan on the
  block's own top-face grid lines, each block interval cut into as many sub-facets as make
  the facets at most `--facet` long (default 0.004): so the slave nodes start exactly below
  master nodes, where the faceted surface is exact, and the chord error between nodes is at
  most facet^2 / (8 R) = 2e-6 (0.04 % of the indentation 0.005). The cap covers the plan
  square [-h, L]^2 (L >= `--cap`, default 0.25, past the contact radius 0.072 by 3.5x; one
  facet row past the symmetry planes, so that a slave node on a plane never falls off the
  master's edge).
* Contact: *CONTACT PAIR, TYPE=NODE TO SURFACE, slave the block's top face (element faces, so
  that each slave node gets a spring area: a quarter of each slave quadrilateral around it,
  as contrail's tributary area), master the cap; frictionless (no *FRICTION).
  *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR with slope K = eps_n = 1e7: CalculiX's
  spring force is p(d) * (spring area) with p = K d [1/2 + atan(d/eps)/pi],
  eps = pi sigma_inf / K, i.e. K d - sigma_inf for d >> eps; contrail's is
  eps_n * A_s * d. The same slope per unit area; the differences: CalculiX's area is the
  current one (co + vold), contrail's the reference one; CalculiX adds the small tension
  sigma_inf (here `--sigma-inf`, default 0.01, 2e-4 of the peak pressure) to open nodes
  within c0 sqrt(area) of the master and subtracts it from closed ones.
* *STATIC, DIRECT: fixed increments of 1/INCREMENTS (4 by default, as the scene).
* Newton tolerance (`--tol`): CalculiX sets a largest residual below 1e-6 (absolute) to zero
  before its tests (nonlingeo.c, "to cope with stress-less temperature calculations"); at
  this model's force scale (the quarter's force 0.14, CalculiX's "average force" 4e-5) its
  residual test is thus an absolute 1e-6, and with its own criteria (`--tol default`) it
  accepts an increment at the first iteration whose residual is under 1e-6, whatever the
  displacement correction. `--tol tight` (the default here) keeps its residual criteria
  but sets C_n = 0 and R_l = -1 in *CONTROLS, PARAMETERS=FIELD, so that an increment ends
  only when the largest displacement correction is below CalculiX's absolute floor 1e-8
  (2e-6 of the sphere's travel): one more Newton iteration, converged as tightly as
  contrail's (relative residual 1e-9).
* Output (.dat): the total reaction force on the cap's nodes (= the contact force on the
  quarter), the contact stresses (CSTR: pressure per slave node) and displacements of the
  block's top-face nodes (for the current positions and areas). `read_ccx.py` reads them.

Usage: hertz_3d_inp.py --elements 8 8 6 [--increments 4] [--out DIR/hertz.inp]
"""
import argparse
import math
import sys

E, NU = 1000.0, 0.3
R, CENTRE_Z = 1.0, 1.0
DEPTH = 0.005
EPS_N = 1.0e7
GRADING = (16.0, 16.0, 0.0625)
ORIGIN = (0.0, 0.0, -1.0)
SIZE = (1.0, 1.0, 1.0)


def graded_coords(length, n, ratio):
    """contrail's `graded_coords`: n elements on [0, length], last / first = ratio."""
    if n == 0:
        return [0.0]
    q = ratio ** (1.0 / (n - 1.0)) if n > 1 else 1.0
    w = [q**i for i in range(n)]
    total = sum(w)
    c, acc = [0.0], 0.0
    for wi in w:
        acc += wi
        c.append(length * acc / total)
    c[n] = length
    return c


def block_grid(elements):
    """The block's node coordinates per axis (absolute)."""
    return [[ORIGIN[a] + v for v in graded_coords(SIZE[a], elements[a], GRADING[a])] for a in range(3)]


def cap_axis(xs, cap, facet, fine):
    """Plan coordinates of the cap's nodes along one axis: the block's grid lines from 0 up to
    the first one at or beyond `cap`, each interval that starts below `fine` cut into
    sub-facets at most `facet` long (the others, out of contact, left whole), and one facet
    before 0."""
    out = [0.0]
    for x0, x1 in zip(xs, xs[1:]):
        m = max(1, math.ceil((x1 - x0) / facet - 1e-12)) if x0 < fine else 1
        out += [x0 + (x1 - x0) * (s + 1) / m for s in range(m)]
        if x1 >= cap:
            break
    return [-(out[1] - out[0])] + out


def num(v):
    """`v` with as many digits as fit CalculiX's 20-character fields."""
    for digits in range(17, 5, -1):
        t = f"{v:.{digits}g}"
        if len(t) <= 20:
            return t
    raise ValueError(v)


def lines(values, per=8):
    vs = list(values)
    return "\n".join(", ".join(str(v) for v in vs[i : i + per]) for i in range(0, len(vs), per))


def deck(elements, increments, facet, fine, cap, thickness, sigma_inf, tol):
    nx, ny, nz = elements
    xs, ys, zs = block_grid(elements)
    out = []
    w = out.append
    w("** contrail hertz-3d in CalculiX: written by benches/calculix/hertz_3d_inp.py")
    w(f"** block {nx}x{ny}x{nz} C3D8I, neo-Hooke E = {E}, nu = {NU}; rigid sphere R = {R} as a")
    w(f"** prescribed C3D8R cap; node-to-surface penalty K = {EPS_N:g}; {increments} fixed increments")
    w("*HEADING")
    w(f"contrail hertz-3d, block {nx}x{ny}x{nz}")

    # block nodes, numbered as contrail (+1)
    def bid(i, j, k):
        return (k * (ny + 1) + j) * (nx + 1) + i + 1

    w("*NODE, NSET=NBLOCK")
    for k, z in enumerate(zs):
        for j, y in enumerate(ys):
            for i, x in enumerate(xs):
                w(f"{bid(i, j, k)}, {num(x)}, {num(y)}, {num(z)}")
    nblock = (nx + 1) * (ny + 1) * (nz + 1)

    # cap nodes: contact face on the sphere (radius R), a second layer at R - thickness
    cx = cap_axis([x - ORIGIN[0] for x in xs], cap, facet, fine)
    cy = cap_axis([y - ORIGIN[1] for y in ys], cap, facet, fine)
    mx, my = len(cx), len(cy)
    if (cx[-1] ** 2 + cy[-1] ** 2) >= (0.9 * R) ** 2:
        sys.exit(f"cap too wide for the sphere: corner ({cx[-1]}, {cy[-1]})")
    base = 10 ** len(str(nblock))  # cap node ids start at the next power of ten

    def cid(p, q, layer):
        return base + layer * mx * my + q * mx + p + 1

    w("*NODE, NSET=NCAP")
    for layer, rad in enumerate((R, R - thickness)):
        for q, y in enumerate(cy):
            for p, x in enumerate(cx):
                zs_ = CENTRE_Z - math.sqrt(R * R - x * x - y * y)  # on the sphere, below the centre
                s = rad / R
                w(f"{cid(p, q, layer)}, {num(s * x)}, {num(s * y)}, {num(CENTRE_Z + s * (zs_ - CENTRE_Z))}")

    # block elements (Abaqus/CalculiX C3D8 order = contrail's: bottom face ccw from above, then top)
    w("*ELEMENT, TYPE=C3D8I, ELSET=EBLOCK")
    eid = 0
    top = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                eid += 1
                b = [bid(i, j, k), bid(i + 1, j, k), bid(i + 1, j + 1, k), bid(i, j + 1, k)]
                t = [bid(i, j, k + 1), bid(i + 1, j, k + 1), bid(i + 1, j + 1, k + 1), bid(i, j + 1, k + 1)]
                w(", ".join(str(v) for v in [eid] + b + t))
                if k == nz - 1:
                    top.append(eid)
    # cap elements: face 1 (nodes 1-4) on the sphere (bottom, facing the block), face 2 inside
    w("*ELEMENT, TYPE=C3D8R, ELSET=ECAP")
    ebase = 10 ** len(str(eid))
    ncap_el = 0
    for q in range(my - 1):
        for p in range(mx - 1):
            ncap_el += 1
            b = [cid(p, q, 0), cid(p + 1, q, 0), cid(p + 1, q + 1, 0), cid(p, q + 1, 0)]
            t = [cid(p, q, 1), cid(p + 1, q, 1), cid(p + 1, q + 1, 1), cid(p, q + 1, 1)]
            w(", ".join(str(v) for v in [ebase + ncap_el] + b + t))

    w("*ELSET, ELSET=ETOP")
    w(lines(top))
    w("*NSET, NSET=NTOP")
    w(lines(bid(i, j, nz) for j in range(ny + 1) for i in range(nx + 1)))
    w("*NSET, NSET=NZMIN")
    w(lines(bid(i, j, 0) for j in range(ny + 1) for i in range(nx + 1)))
    w("*NSET, NSET=NXMIN")
    w(lines(bid(0, j, k) for k in range(nz + 1) for j in range(ny + 1)))
    w("*NSET, NSET=NYMIN")
    w(lines(bid(i, 0, k) for k in range(nz + 1) for i in range(nx + 1)))

    w("*SURFACE, NAME=SLAVE, TYPE=ELEMENT")
    w("ETOP, S2")
    w("*SURFACE, NAME=MASTER, TYPE=ELEMENT")
    w("ECAP, S1")

    mu = E / (2.0 * (1.0 + NU))
    kappa = E / (3.0 * (1.0 - 2.0 * NU))
    w("*MATERIAL, NAME=NEOHOOKE")
    w("*HYPERELASTIC, NEO HOOKE")
    w(f"{num(mu / 2.0)}, {num(2.0 / kappa)}")
    w("*MATERIAL, NAME=RIGIDCAP")
    w("*ELASTIC")
    w("1e9, 0.3")
    w("*SOLID SECTION, ELSET=EBLOCK, MATERIAL=NEOHOOKE")
    w("*SOLID SECTION, ELSET=ECAP, MATERIAL=RIGIDCAP")

    w("*SURFACE INTERACTION, NAME=SI1")
    w("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR")
    w(f"{EPS_N:g}, {sigma_inf:g}")
    w("*CONTACT PAIR, INTERACTION=SI1, TYPE=NODE TO SURFACE")
    w("SLAVE, MASTER")

    w("*BOUNDARY")
    w("NZMIN, 3, 3, 0.")
    w("NXMIN, 1, 1, 0.")
    w("NYMIN, 2, 2, 0.")
    w("NCAP, 1, 2, 0.")

    w(f"*STEP, NLGEOM, INC={10 * increments}")
    w("*STATIC, DIRECT")
    w(f"{num(1.0 / increments)}, 1.0")
    if tol == "tight":
        # R_n, C_n, q0, qu, R_p, eps, C_eps, R_l: CalculiX's defaults but C_n = 0 and R_l = -1,
        # so that only its absolute floor on the displacement correction (1e-8) ends the
        # iterations (see the module's doc)
        w("*CONTROLS, PARAMETERS=FIELD")
        w("0.005, 0., , , 0.02, 1e-5, 1e-3, -1.")
    elif tol != "default":
        sys.exit(f"--tol {tol}: 'tight' or 'default'")
    w("*BOUNDARY")
    w(f"NCAP, 3, 3, {-DEPTH}")
    w("*NODE PRINT, NSET=NCAP, TOTALS=ONLY")
    w("RF")
    w("*NODE PRINT, NSET=NTOP")
    w("U")
    w("*CONTACT PRINT")
    w("CSTR")
    w("*END STEP")
    return "\n".join(out) + "\n", ncap_el


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--elements", nargs=3, type=int, required=True, metavar=("NX", "NY", "NZ"))
    ap.add_argument("--increments", type=int, default=4)
    ap.add_argument("--facet", type=float, default=0.004, help="longest cap facet edge in plan")
    ap.add_argument("--fine", type=float, default=0.12, help="facets are refined where the plan coordinate is below this")
    ap.add_argument("--cap", type=float, default=0.25, help="the cap covers the plan square up to at least this")
    ap.add_argument("--thickness", type=float, default=0.05, help="cap layer thickness")
    ap.add_argument("--sigma-inf", type=float, default=0.01, help="tension at large clearance")
    ap.add_argument("--tol", default="tight", choices=["tight", "default"], help="Newton criteria (see above)")
    ap.add_argument("--out", default="-")
    a = ap.parse_args()
    text, ncap = deck(a.elements, a.increments, a.facet, a.fine, a.cap, a.thickness, a.sigma_inf, a.tol)
    if a.out == "-":
        sys.stdout.write(text)
    else:
        with open(a.out, "w") as f:
            f.write(text)
    print(f"hertz_3d_inp: {a.elements}, {ncap} cap facets", file=sys.stderr)


if __name__ == "__main__":
    main()
