//! Structured hexahedral mesh of a hollow hemisphere (a thick spherical shell cut at its
//! equator), the dome below the centre: the twisting-hemisphere benchmark's body.
//!
//! The shell's mid-surface is meshed as the lower half of an equiangular "cubed sphere": the
//! bottom face of the cube `[-1, 1]³` (`n × n` cells) and the lower halves of its four sides
//! (`n × n/2` cells each), every lattice coordinate `a ∈ [-1, 1]` placed at `tan(π/4 · a)` and
//! the point projected radially onto the sphere. The equator (`z` = the centre's) is a lattice
//! line, so the rim is flat; the cube's corners become nodes shared by three cells, and no
//! cell is degenerate (unlike a latitude–longitude mesh at its pole). `layers` hexahedra go
//! through the thickness, evenly spaced in radius.

use super::box_mesh::BoxMesh;
use super::hex_boundary::{boundary_quads, face_node_sets};
use crate::contact3d::vec3::{cross, dot, norm, sub};
use std::collections::{BTreeMap, HashMap};

/// The hollow hemisphere `inner ≤ |x − centre| ≤ outer`, `z ≤ centre_z`: `3 n²` cells per
/// layer (`n` even, ≥ 2), `layers ≥ 1` through the thickness. Node sets and faces: `outer`
/// (the dome), `inner`, `rim` (the flat annulus at the equator, outward normal +z), and the
/// set `all`.
pub fn hemisphere_shell(centre: [f64; 3], radius: [f64; 2], n: usize, layers: usize) -> BoxMesh {
    let (dirs, quads) = lower_cubed_sphere(n);
    let s = dirs.len();
    let mut nodes = Vec::with_capacity(s * (layers + 1));
    for l in 0..=layers {
        let r = radius[0] + (radius[1] - radius[0]) * l as f64 / layers as f64;
        nodes.extend(dirs.iter().map(|d| std::array::from_fn(|c| centre[c] + r * d[c])));
    }
    let mut hexes = Vec::with_capacity(quads.len() * layers);
    for l in 0..layers {
        for q in &quads {
            let [a, b, c, d] = q.map(|v| v + l * s);
            hexes.push([a, b, c, d, a + s, b + s, c + s, d + s]);
        }
    }
    let scale = radius[1].abs().max(1e-300);
    let on_radius = |x: &[f64; 3], r: f64| (norm(sub(*x, centre)) - r).abs() <= 1e-9 * scale;
    let on_rim = |x: &[f64; 3]| (x[2] - centre[2]).abs() <= 1e-9 * scale;
    let mut faces: BTreeMap<String, Vec<[usize; 4]>> = BTreeMap::new();
    for f in boundary_quads(&hexes) {
        let all = |test: &dyn Fn(&[f64; 3]) -> bool| f.iter().all(|&v| test(&nodes[v]));
        let name = if all(&on_rim) {
            "rim"
        } else if all(&|x| on_radius(x, radius[1])) {
            "outer"
        } else {
            "inner"
        };
        faces.entry(name.to_string()).or_default().push(f);
    }
    let mut node_sets = face_node_sets(&faces);
    node_sets.insert("all".into(), (0..nodes.len()).collect());
    BoxMesh {
        nodes,
        hexes,
        node_sets,
        faces,
    }
}

/// The unit directions of the lower half of the equiangular cubed sphere and its cells,
/// counter-clockwise seen from outside (normal `(x₁ − x₀) × (x₃ − x₀)` outward).
fn lower_cubed_sphere(n: usize) -> (Vec<[f64; 3]>, Vec<[usize; 4]>) {
    let half = n / 2;
    let at = |i: usize| (std::f64::consts::FRAC_PI_4 * (2.0 * i as f64 / n as f64 - 1.0)).tan();
    let mut index: HashMap<[usize; 3], usize> = HashMap::new();
    let mut dirs: Vec<[f64; 3]> = Vec::new();
    let mut id = |p: [usize; 3]| {
        *index.entry(p).or_insert_with(|| {
            let c = [at(p[0]), at(p[1]), at(p[2])];
            let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            dirs.push(c.map(|v| v / len));
            dirs.len() - 1
        })
    };
    let mut cells: Vec<[usize; 4]> = Vec::with_capacity(3 * n * n);
    for i in 0..n {
        for j in 0..n {
            cells.push([[i, j, 0], [i + 1, j, 0], [i + 1, j + 1, 0], [i, j + 1, 0]].map(&mut id));
        }
    }
    for side in [0, n] {
        for a in 0..n {
            for k in 0..half {
                cells.push([[side, a, k], [side, a + 1, k], [side, a + 1, k + 1], [side, a, k + 1]].map(&mut id));
                cells.push([[a, side, k], [a + 1, side, k], [a + 1, side, k + 1], [a, side, k + 1]].map(&mut id));
            }
        }
    }
    for c in &mut cells {
        if outward_flux(c.map(|v| dirs[v])) < 0.0 {
            *c = [c[0], c[3], c[2], c[1]];
        }
    }
    (dirs, cells)
}

/// `((x₁ − x₀) × (x₃ − x₀)) · Σ xᵢ` for a quadrilateral about a centre at the origin:
/// positive when it turns counter-clockwise seen from outside.
fn outward_flux(x: [[f64; 3]; 4]) -> f64 {
    let normal = cross(sub(x[1], x[0]), sub(x[3], x[0]));
    dot(normal, std::array::from_fn(|k| x[0][k] + x[1][k] + x[2][k] + x[3][k]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8::{Hex8Geometry, Hex8Kind};

    #[test]
    fn the_shell_has_its_counts_radii_rim_and_positive_volumes() {
        let (n, layers) = (4, 2);
        let m = hemisphere_shell([0.5, -1.0, 2.0], [2.0 / 3.0, 1.0], n, layers);
        assert_eq!(m.hexes.len(), 3 * n * n * layers);
        let surface = (n + 1) * (n + 1) + 4 * n * (n / 2);
        assert_eq!(m.nodes.len(), surface * (layers + 1));
        assert_eq!(m.faces["outer"].len(), 3 * n * n);
        assert_eq!(m.faces["inner"].len(), 3 * n * n);
        assert_eq!(m.faces["rim"].len(), 4 * n * layers);
        for &v in &m.node_sets["rim"] {
            assert!((m.nodes[v][2] - 2.0).abs() < 1e-12);
        }
        for &v in &m.node_sets["outer"] {
            assert!((norm(sub(m.nodes[v], [0.5, -1.0, 2.0])) - 1.0).abs() < 1e-12);
        }
        let mut volume = 0.0;
        for h in &m.hexes {
            let v = Hex8Geometry::new(Hex8Kind::Hex8, &h.map(|i| m.nodes[i]))
                .expect("a valid cell")
                .volume();
            volume += v;
        }
        // the volume of the hexahedra approaches (2π/3)(R³ − r³) from below as n grows
        let exact = 2.0 * std::f64::consts::PI / 3.0 * (1.0 - (2.0f64 / 3.0).powi(3));
        assert!(volume < exact && volume > 0.9 * exact, "{volume} against {exact}");
    }

    #[test]
    fn faces_point_out_of_the_shell() {
        let m = hemisphere_shell([0.0; 3], [0.5, 1.0], 6, 1);
        for (name, quads) in &m.faces {
            for q in quads {
                let x = q.map(|v| m.nodes[v]);
                let along = match name.as_str() {
                    "rim" => cross(sub(x[1], x[0]), sub(x[3], x[0]))[2],
                    "outer" => outward_flux(x),
                    _ => -outward_flux(x),
                };
                assert!(along > 0.0, "face `{name}` points inwards");
            }
        }
    }
}
