#!/usr/bin/env python3
"""Write a Gmsh MSH 4.1 mesh of 8-node hexahedra: the quarter (x, y >= 0) of the upper half
(0 <= z <= h) of a disc of radius r, a mapped "butterfly" mesh (a square core of side
r/2 and two blocks between its outer edges and the rim), with the physical surfaces
bottom (z = 0), top (z = h), xsym (x = 0), ysym (y = 0), side (the rim) and the volume disc.

    python3 tests/data/make-disc-quarter.py N M NZ > tests/data/disc-quarter.msh

N elements along each edge of the core, M from the core to the rim, NZ through the height
(defaults 8 8 8; r = 1, h = 0.5). Used by tests/disc_barrelling.rs.
"""
import math
import sys

R, H = 1.0, 0.5


def section(n, m):
    """The plane nodes (x, y) and quadrilaterals (counter-clockwise) of the quarter disc."""
    nodes, index = [], {}

    def node(p):
        key = (round(p[0], 12), round(p[1], 12))
        if key not in index:
            index[key] = len(nodes)
            nodes.append(p)
        return index[key]

    s = 0.5 * R
    core = [[node((s * i / n, s * j / n)) for j in range(n + 1)] for i in range(n + 1)]
    quads = [(core[i][j], core[i + 1][j], core[i + 1][j + 1], core[i][j + 1]) for i in range(n) for j in range(n)]
    # block 1: from the core's edge x = s out to the rim, angle 0..45 degrees along j
    b1 = [[None] * (n + 1) for _ in range(m + 1)]
    # block 2: from the core's edge y = s out to the rim, angle 90..45 degrees along i
    b2 = [[None] * (n + 1) for _ in range(m + 1)]
    for k in range(m + 1):
        f = k / m
        for j in range(n + 1):
            a = 0.25 * math.pi * j / n
            inner = (s, s * j / n)
            b1[k][j] = node(((1 - f) * inner[0] + f * R * math.cos(a), (1 - f) * inner[1] + f * R * math.sin(a)))
        for i in range(n + 1):
            a = 0.5 * math.pi - 0.25 * math.pi * i / n
            inner = (s * i / n, s)
            b2[k][i] = node(((1 - f) * inner[0] + f * R * math.cos(a), (1 - f) * inner[1] + f * R * math.sin(a)))
    for k in range(m):
        for j in range(n):
            quads.append((b1[k][j], b1[k + 1][j], b1[k + 1][j + 1], b1[k][j + 1]))
        for i in range(n):
            quads.append((b2[k][i], b2[k][i + 1], b2[k + 1][i + 1], b2[k + 1][i]))
    for q in quads:
        (x0, y0), (x1, y1), (x3, y3) = nodes[q[0]], nodes[q[1]], nodes[q[3]]
        assert (x1 - x0) * (y3 - y0) - (y1 - y0) * (x3 - x0) > 0, "counter-clockwise"
    return nodes, quads


def main():
    n, m, nz = (int(a) for a in (sys.argv[1:4] if len(sys.argv) > 3 else (8, 8, 8)))
    plane, quads = section(n, m)
    np_ = len(plane)
    tag = lambda p, k: 1 + k * np_ + p  # noqa: E731  (node tag of plane node p at level k)
    hexes = [tuple(tag(p, k) for p in q) + tuple(tag(p, k + 1) for p in q) for k in range(nz) for q in quads]
    eps = 1e-9
    rim = [i for i, (x, y) in enumerate(plane) if abs(math.hypot(x, y) - R) < eps]
    faces = {"bottom": [], "top": [], "xsym": [], "ysym": [], "side": []}
    for q in quads:
        faces["bottom"].append(tuple(tag(p, 0) for p in q))
        faces["top"].append(tuple(tag(p, nz) for p in q))
    edges = {(q[a], q[(a + 1) % 4]) for q in quads for a in range(4)}
    for (a, b) in edges:
        if (b, a) in edges:
            continue  # interior edge
        (xa, ya), (xb, yb) = plane[a], plane[b]
        name = "xsym" if abs(xa) < eps and abs(xb) < eps else "ysym" if abs(ya) < eps and abs(yb) < eps else "side"
        assert name != "side" or (a in rim and b in rim)
        for k in range(nz):
            faces[name].append((tag(a, k), tag(b, k), tag(b, k + 1), tag(a, k + 1)))
    names = list(faces)
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(names) + 1)]
    out += [f'2 {i + 1} "{nm}"' for i, nm in enumerate(names)]
    out += [f'3 {len(names) + 1} "disc"', "$EndPhysicalNames", "$Entities", f"0 0 {len(names)} 1"]
    out += [f"{i + 1} 0 0 0 {R} {R} {H} 1 {i + 1} 0" for i in range(len(names))]
    out += [f"1 0 0 0 {R} {R} {H} 1 {len(names) + 1} {len(names)} " + " ".join(str(i + 1) for i in range(len(names)))]
    out += ["$EndEntities", "$Nodes"]
    count = np_ * (nz + 1)
    out += [f"1 {count} 1 {count}", f"3 1 0 {count}"]
    out += [str(i + 1) for i in range(count)]
    out += [f"{x!r} {y!r} {H * k / nz!r}" for k in range(nz + 1) for (x, y) in plane]
    out += ["$EndNodes", "$Elements"]
    total = len(hexes) + sum(len(f) for f in faces.values())
    out += [f"{len(names) + 1} {total} 1 {total}"]
    t = 1
    for i, nm in enumerate(names):
        out.append(f"2 {i + 1} 3 {len(faces[nm])}")
        for f in faces[nm]:
            out.append(f"{t} " + " ".join(map(str, f)))
            t += 1
    out.append(f"3 1 5 {len(hexes)}")
    for h in hexes:
        out.append(f"{t} " + " ".join(map(str, h)))
        t += 1
    out += ["$EndElements"]
    print("\n".join(out))


if __name__ == "__main__":
    main()
