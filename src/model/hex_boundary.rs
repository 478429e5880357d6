//! The faces of a hexahedral mesh: the six faces of the kernel's hexahedron (Gmsh/VTK node
//! order) and the boundary of a mesh (the faces that belong to one hexahedron only).

use std::collections::{BTreeMap, HashMap};

/// The faces of the kernel's hexahedron, each with its outward normal `(x₁ − x₀) × (x₃ − x₀)`.
pub const HEX_FACES: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [3, 0, 4, 7],
];

/// The boundary faces of the hexahedra `hexes` (faces met once), outward, in the order met.
pub fn boundary_quads(hexes: &[[usize; 8]]) -> Vec<[usize; 4]> {
    let mut seen: HashMap<[usize; 4], (usize, [usize; 4])> = HashMap::new();
    let mut order = Vec::new();
    for h in hexes {
        for f in HEX_FACES {
            let quad = f.map(|i| h[i]);
            let mut key = quad;
            key.sort_unstable();
            let entry = seen.entry(key).or_insert_with(|| {
                order.push(key);
                (0, quad)
            });
            entry.0 += 1;
        }
    }
    (order.iter())
        .filter_map(|k| seen.get(k).filter(|(n, _)| *n == 1).map(|(_, q)| *q))
        .collect()
}

/// The node set of each named face: its quadrilaterals' distinct nodes, ascending.
pub fn face_node_sets(faces: &BTreeMap<String, Vec<[usize; 4]>>) -> BTreeMap<String, Vec<usize>> {
    (faces.iter())
        .map(|(name, quads)| {
            let mut set: Vec<usize> = quads.iter().flatten().copied().collect();
            set.sort_unstable();
            set.dedup();
            (name.clone(), set)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_hexahedra_side_by_side_have_ten_outward_boundary_faces() {
        // unit cubes [0,1]³ and [1,2]×[0,1]²; nodes 0–3 at z = 0 (counter-clockwise), 4–7 above
        let a = [0, 1, 2, 3, 4, 5, 6, 7];
        let b = [1, 8, 9, 2, 5, 10, 11, 6];
        let x = |n: usize| -> [f64; 3] {
            let base = [
                [0., 0.],
                [1., 0.],
                [1., 1.],
                [0., 1.],
                [0., 0.],
                [1., 0.],
                [1., 1.],
                [0., 1.],
            ];
            let extra = [[2., 0.], [2., 1.], [2., 0.], [2., 1.]];
            let (xy, z) = if n < 8 {
                (base[n], (n / 4) as f64)
            } else {
                (extra[n - 8], ((n - 8) / 2) as f64)
            };
            [xy[0], xy[1], z]
        };
        let faces = boundary_quads(&[a, b]);
        assert_eq!(faces.len(), 10);
        assert!(
            !faces.iter().any(|f| f.iter().all(|n| [1, 2, 5, 6].contains(n))),
            "the shared face is inside"
        );
        for f in &faces {
            let (p0, p1, p3) = (x(f[0]), x(f[1]), x(f[3]));
            let (u, v) = ([0, 1, 2].map(|c| p1[c] - p0[c]), [0, 1, 2].map(|c| p3[c] - p0[c]));
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let centre = [0, 1, 2].map(|c| f.iter().map(|&i| x(i)[c]).sum::<f64>() / 4.0);
            let inside = if centre[0] < 1.0 {
                [0.5, 0.5, 0.5]
            } else {
                [1.5, 0.5, 0.5]
            };
            let out: f64 = (0..3).map(|c| n[c] * (centre[c] - inside[c])).sum();
            assert!(out > 0.0, "face {f:?} points inwards");
        }
    }
}
