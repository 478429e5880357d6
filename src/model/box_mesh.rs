//! Structured hexahedral mesh of a box, the 3D counterpart of [`super::mesh::RectMesh`].

use super::mesh::graded_coords;
use std::collections::BTreeMap;

/// Hexahedral mesh of the box `origin .. origin + size`, optionally graded per axis.
#[derive(Debug, Clone)]
pub struct BoxMesh {
    /// Node coordinates, `i` (x) fastest, then `j` (y), then `k` (z).
    pub nodes: Vec<[f64; 3]>,
    /// Hexahedra in Gmsh/VTK order: the bottom face (`z` low) counter-clockwise seen from
    /// above, then the top face in the same order (`det J > 0`).
    pub hexes: Vec<[usize; 8]>,
    /// Named node sets: `xmin`, `xmax`, `ymin`, `ymax`, `zmin`, `zmax` (the six sides) and
    /// `all`.
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Named boundary faces (the six sides), as quadrilaterals counter-clockwise seen from
    /// outside (their normal `(x₁ − x₀) × (x₃ − x₀)` points out of the box).
    pub faces: BTreeMap<String, Vec<[usize; 4]>>,
}

impl BoxMesh {
    /// The summed volume of the hexahedra (a test of generated meshes).
    #[cfg(test)]
    pub fn volume(&self) -> f64 {
        use crate::element::hex8::{Hex8Geometry, Hex8Kind};
        (self.hexes.iter())
            .map(|h| {
                Hex8Geometry::new(Hex8Kind::Hex8, &h.map(|i| self.nodes[i]))
                    .expect("a valid cell")
                    .volume()
            })
            .sum()
    }

    /// `elements = [nx, ny, nz]` (each ≥ 1); `grading` per axis is the last element over
    /// the first (1 = uniform).
    pub fn new(origin: [f64; 3], size: [f64; 3], elements: [usize; 3], grading: [f64; 3]) -> Self {
        let c: [Vec<f64>; 3] = std::array::from_fn(|a| graded_coords(size[a], elements[a], grading[a]));
        Self::on_grid(origin, &c)
    }

    /// The mesh of the grid `origin + (x[i], y[j], z[k])` (each list increasing from 0).
    pub fn on_grid(origin: [f64; 3], c: &[Vec<f64>; 3]) -> Self {
        let [nx, ny, nz] = [0, 1, 2].map(|a| c[a].len().saturating_sub(1));
        let id = |i: usize, j: usize, k: usize| (k * (ny + 1) + j) * (nx + 1) + i;
        let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
        for z in &c[2] {
            for y in &c[1] {
                for x in &c[0] {
                    nodes.push([origin[0] + x, origin[1] + y, origin[2] + z]);
                }
            }
        }
        let mut hexes = Vec::with_capacity(nx * ny * nz);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let b = [id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k)];
                    let t = [
                        id(i, j, k + 1),
                        id(i + 1, j, k + 1),
                        id(i + 1, j + 1, k + 1),
                        id(i, j + 1, k + 1),
                    ];
                    hexes.push([b[0], b[1], b[2], b[3], t[0], t[1], t[2], t[3]]);
                }
            }
        }
        let n = [nx, ny, nz];
        let mut node_sets = BTreeMap::new();
        let mut faces = BTreeMap::new();
        for (axis, names) in [["xmin", "xmax"], ["ymin", "ymax"], ["zmin", "zmax"]]
            .iter()
            .enumerate()
        {
            for (side, name) in names.iter().enumerate() {
                let at = side * n[axis];
                // the two other axes, in the order that makes (a × b) point along +axis
                let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
                let node = |p: usize, q: usize| {
                    let mut ijk = [0; 3];
                    ijk[axis] = at;
                    ijk[a] = p;
                    ijk[b] = q;
                    id(ijk[0], ijk[1], ijk[2])
                };
                let set: Vec<usize> = (0..=n[b]).flat_map(|q| (0..=n[a]).map(move |p| node(p, q))).collect();
                let mut quads = Vec::with_capacity(n[a] * n[b]);
                for q in 0..n[b] {
                    for p in 0..n[a] {
                        let ccw = [node(p, q), node(p + 1, q), node(p + 1, q + 1), node(p, q + 1)];
                        // outward: +axis on the max side, −axis on the min side (reversed)
                        quads.push(match side {
                            1 => ccw,
                            _ => [ccw[0], ccw[3], ccw[2], ccw[1]],
                        });
                    }
                }
                node_sets.insert(name.to_string(), set);
                faces.insert(name.to_string(), quads);
            }
        }
        node_sets.insert("all".into(), (0..nodes.len()).collect());
        BoxMesh {
            nodes,
            hexes,
            node_sets,
            faces,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cross(u: [f64; 3], v: [f64; 3]) -> [f64; 3] {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    }

    #[test]
    fn a_box_has_its_counts_sets_and_outward_faces() {
        let m = BoxMesh::new([1.0, 2.0, 3.0], [2.0, 1.0, 0.5], [3, 2, 1], [1.0, 2.0, 1.0]);
        assert_eq!((m.nodes.len(), m.hexes.len()), (4 * 3 * 2, 6));
        assert_eq!(m.node_sets["xmin"].len(), 3 * 2);
        assert_eq!(m.faces["zmax"].len(), 6);
        let centre = [2.0, 2.5, 3.25];
        for (name, quads) in &m.faces {
            for q in quads {
                let x = q.map(|n| m.nodes[n]);
                let d = |p: [f64; 3], o: [f64; 3]| [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
                let nrm = cross(d(x[1], x[0]), d(x[3], x[0]));
                let out = d(x[0], centre);
                let dot: f64 = (0..3).map(|c| nrm[c] * out[c]).sum();
                assert!(dot > 0.0, "face {name} points inwards");
                assert!(q.iter().all(|n| m.node_sets[name].contains(n)));
            }
        }
        // every hexahedron has a positive volume (det J at the centre)
        for h in &m.hexes {
            let x = h.map(|n| m.nodes[n]);
            let d = |a: usize, b: usize| [x[b][0] - x[a][0], x[b][1] - x[a][1], x[b][2] - x[a][2]];
            let (e1, e2, e3) = (d(0, 1), d(0, 3), d(0, 4));
            let c = cross(e1, e2);
            assert!(c[0] * e3[0] + c[1] * e3[1] + c[2] * e3[2] > 0.0);
        }
    }
}
