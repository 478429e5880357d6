"""Hertz point contact (Johnson, Contact Mechanics (1985) §4.2) and the measures of
`tests/hertz_sphere_3d.rs`, shared by `read_ccx.py` and `read_contrail.py` so that both
columns of the comparison mean the same thing.

Measures, from the slave nodes in contact at the last increment of the quarter model, each
with its normal force N, current position (x, y) and reference tributary area A:
  F  = 4 * sum(N)                               (the full model's force)
  a  = sqrt(5/2 * sum(r^2 N) / sum(N))          (Hertz: sum(r^2 N)/sum(N) = 2 a^2 / 5)
  p0 = N / A of the closed node nearest the axis
References: a and p0 against Hertz for the measured F (as the test does); F against Hertz
for the indentation d in a half-space (the block, 14 a deep and held at its bottom, is
stiffer than a half-space, so this error is mostly the domain's, the same in both codes).
"""
import math

E, NU, R, DEPTH = 1000.0, 0.3, 1.0, 0.005
E_STAR = E / (1.0 - NU * NU)


def hertz_of_force(force):
    a = (3.0 * force * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    return a, 3.0 * force / (2.0 * math.pi * a * a)


def hertz_force(depth=DEPTH):
    return 4.0 / 3.0 * E_STAR * math.sqrt(R) * depth**1.5


def measure(points):
    """points: (x, y, N, A) of the closed slave nodes. Returns a dict of the measures."""
    if not points:
        raise ValueError("no slave node in contact")
    quarter = sum(p[2] for p in points)
    second = sum((p[0] ** 2 + p[1] ** 2) * p[2] for p in points) / quarter
    axis = min(points, key=lambda p: math.hypot(p[0], p[1]))
    force = 4.0 * quarter
    a_h, p0_h = hertz_of_force(force)
    a, p0 = math.sqrt(2.5 * second), axis[2] / axis[3]
    f_h = hertz_force()
    return {
        "F": force,
        "a": a,
        "p0": p0,
        "closed": len(points),
        "F_err": force / f_h - 1.0,
        "a_err": a / a_h - 1.0,
        "p0_err": p0 / p0_h - 1.0,
        "F_hertz": f_h,
        "a_hertz": a_h,
        "p0_hertz": p0_h,
    }


def quad_area(x):
    """Area of the bilinear quadrilateral through the corners x (2x2 Gauss, as contrail's
    `quad_area` and CalculiX's spring area)."""
    xi_, eta_ = (-1.0, 1.0, 1.0, -1.0), (-1.0, -1.0, 1.0, 1.0)
    g = 1.0 / math.sqrt(3.0)
    total = 0.0
    for xi, eta in ((-g, -g), (g, -g), (g, g), (-g, g)):
        a, b = [0.0] * 3, [0.0] * 3
        for k in range(4):
            for c in range(3):
                a[c] += 0.25 * xi_[k] * (1.0 + eta_[k] * eta) * x[k][c]
                b[c] += 0.25 * eta_[k] * (1.0 + xi_[k] * xi) * x[k][c]
        n = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
        total += math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
    return total


def tributary_areas(coords, quads):
    """A quarter of each quadrilateral's area to each of its corners."""
    area = {}
    for q in quads:
        a = quad_area([coords[n] for n in q])
        for n in q:
            area[n] = area.get(n, 0.0) + 0.25 * a
    return area


def line(code, m, extra):
    """One `key=value` line for the bench script."""
    fields = {"code": code, **extra, **{k: f"{v:.7g}" if isinstance(v, float) else v for k, v in m.items()}}
    return " ".join(f"{k}={v}" for k, v in fields.items())


def report(code, label, m, extra, note=""):
    """Print the bench script's line (stdout) and a readable summary (stderr) of one run;
    exit non-zero when F, a or p0 is not finite."""
    import sys

    print(line(code, m, extra))
    print(
        f"{code} {label}: F = {m['F']:.6f} ({note}Hertz for d: {m['F_hertz']:.6f}, {100 * m['F_err']:+.2f} %), "
        f"a = {m['a']:.5f} (Hertz {m['a_hertz']:.5f}, {100 * m['a_err']:+.2f} %), "
        f"p0 = {m['p0']:.3f} (Hertz {m['p0_hertz']:.3f}, {100 * m['p0_err']:+.2f} %), "
        f"{m['closed']} nodes closed, {extra['iterations']} Newton iterations",
        file=sys.stderr,
    )
    for k in ("F", "a", "p0"):
        if not math.isfinite(m[k]):
            print(f"{code}: {k} is not finite", file=sys.stderr)
            sys.exit(1)

