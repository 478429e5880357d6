//! Structured hexahedral meshes of thick spherical shells: the hollow hemisphere of the
//! twisting-hemisphere benchmark (the dome below the centre), an octant of a hollow sphere (the
//! symmetric model of spheres pressed between plates) and a whole hollow sphere.
//!
//! The shell's mid-surface is meshed as an equiangular "cubed sphere": each face of the cube
//! `[-1, 1]³` carries `n × n` cells, every lattice coordinate `a ∈ [-1, 1]` placed at
//! `tan(π/4 · a)` and the point projected radially onto the sphere. A part keeps the cells on
//! its side of the coordinate planes through the centre; `n` even makes those planes lattice
//! lines, so the hemisphere's rim and the octant's symmetry faces are flat. The cube's corners
//! become nodes shared by three cells, and no cell is degenerate (unlike a latitude–longitude
//! mesh at its pole). `layers` hexahedra go through the thickness, evenly spaced in radius.

use super::box_mesh::BoxMesh;
use super::hex_boundary::{boundary_quads, face_node_sets};
use crate::contact3d::vec3::{cross, dot, norm, sub};
use std::collections::{BTreeMap, HashMap};

/// Which part of a hollow sphere a shell mesh is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShellPart {
    /// `z ≤ centre_z`: the flat annulus at the equator is the face `rim` (outward normal +z).
    LowerHalf,
    /// `x, y, z ≥` the centre's: the faces on the three symmetry planes are `xmin`, `ymin`
    /// and `zmin`.
    Octant,
    /// The whole sphere: only `outer` and `inner`.
    Whole,
}

impl ShellPart {
    /// Whether a point of the cube `[-1, 1]³` (a cell's centre) lies in this part.
    fn keeps(self, c: [f64; 3]) -> bool {
        match self {
            ShellPart::LowerHalf => c[2] < 0.0,
            ShellPart::Octant => c.iter().all(|&v| v > 0.0),
            ShellPart::Whole => true,
        }
    }

    /// Cells and nodes of one spherical surface of this part with `n` cells along a cube
    /// edge (`n` even).
    pub fn surface_counts(self, n: usize) -> (usize, usize) {
        let h = n / 2;
        match self {
            ShellPart::LowerHalf => (3 * n * n, (n + 1) * (n + 1) + 4 * n * h),
            ShellPart::Octant => (3 * h * h, 3 * h * h + 3 * h + 1),
            ShellPart::Whole => (6 * n * n, 6 * n * n + 2),
        }
    }
}

/// The hollow hemisphere `inner ≤ |x − centre| ≤ outer`, `z ≤ centre_z`: `3 n²` cells per
/// layer (`n` even, ≥ 2), `layers ≥ 1` through the thickness. Node sets and faces: `outer`
/// (the dome), `inner`, `rim` (the flat annulus at the equator, outward normal +z), and the
/// set `all`.
pub fn hemisphere_shell(centre: [f64; 3], radius: [f64; 2], n: usize, layers: usize) -> BoxMesh {
    sphere_shell(centre, radius, (n, layers), ShellPart::LowerHalf)
}

/// The part `part` of the hollow sphere `inner ≤ |x − centre| ≤ outer`: `n` cells along an
/// edge of the cube (`n` even, ≥ 2), `layers ≥ 1` through the thickness. Node sets and faces:
/// `outer`, `inner`, the flat faces of the part (`rim`, or `xmin`, `ymin`, `zmin`), and the
/// set `all`.
pub fn sphere_shell(centre: [f64; 3], radius: [f64; 2], (n, layers): (usize, usize), part: ShellPart) -> BoxMesh {
    let (dirs, quads) = cubed_sphere(n, part);
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
    let on_plane = |x: &[f64; 3], k: usize| (x[k] - centre[k]).abs() <= 1e-9 * scale;
    let mut faces: BTreeMap<String, Vec<[usize; 4]>> = BTreeMap::new();
    for f in boundary_quads(&hexes) {
        let all = |test: &dyn Fn(&[f64; 3]) -> bool| f.iter().all(|&v| test(&nodes[v]));
        let plane = (0..3).find(|&k| all(&|x| on_plane(x, k)));
        let name = match (plane, part) {
            (Some(_), ShellPart::LowerHalf) => "rim",
            (Some(k), _) => ["xmin", "ymin", "zmin"][k],
            (None, _) if all(&|x| on_radius(x, radius[1])) => "outer",
            (None, _) => "inner",
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

/// The unit directions of the part `part` of the equiangular cubed sphere and its cells,
/// counter-clockwise seen from outside (normal `(x₁ − x₀) × (x₃ − x₀)` outward). Cells come
/// face by face: `z = −1`, `z = +1`, then the sides `x = ∓1` and `y = ∓1` by columns.
fn cubed_sphere(n: usize, part: ShellPart) -> (Vec<[f64; 3]>, Vec<[usize; 4]>) {
    let lattice = |i: usize| 2.0 * i as f64 / n as f64 - 1.0;
    let at = |i: usize| (std::f64::consts::FRAC_PI_4 * lattice(i)).tan();
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
    let mut cells: Vec<[usize; 4]> = Vec::with_capacity(6 * n * n);
    let mut add = |cell: [[usize; 3]; 4]| {
        let centre: [f64; 3] = std::array::from_fn(|k| cell.iter().map(|p| lattice(p[k])).sum::<f64>() / 4.0);
        if part.keeps(centre) {
            cells.push(cell.map(&mut id));
        }
    };
    for side in [0, n] {
        for i in 0..n {
            for j in 0..n {
                add([[i, j, side], [i + 1, j, side], [i + 1, j + 1, side], [i, j + 1, side]]);
            }
        }
    }
    for side in [0, n] {
        for a in 0..n {
            for k in 0..n {
                add([[side, a, k], [side, a + 1, k], [side, a + 1, k + 1], [side, a, k + 1]]);
                add([[a, side, k], [a + 1, side, k], [a + 1, side, k + 1], [a, side, k + 1]]);
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
        let volume = m.volume();
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

    #[test]
    fn octant_and_whole_shells_have_their_counts_planes_and_volumes() {
        let (centre, n, layers) = ([0.3, -0.2, 1.0], 6, 2);
        let shell = (1.0f64.powi(3) - 0.8f64.powi(3)) * 4.0 * std::f64::consts::PI / 3.0;
        for (part, share) in [(ShellPart::Octant, 0.125), (ShellPart::Whole, 1.0)] {
            let m = sphere_shell(centre, [0.8, 1.0], (n, layers), part);
            let (cells, surface) = part.surface_counts(n);
            assert_eq!(m.hexes.len(), cells * layers, "{part:?}");
            assert_eq!(m.nodes.len(), surface * (layers + 1), "{part:?}");
            assert_eq!(m.faces["outer"].len(), cells);
            assert_eq!(m.faces["inner"].len(), cells);
            let v = m.volume();
            assert!(v < share * shell && v > 0.97 * share * shell, "{part:?}: {v}");
        }
        let m = sphere_shell(centre, [0.8, 1.0], (n, layers), ShellPart::Octant);
        for (k, name) in ["xmin", "ymin", "zmin"].iter().enumerate() {
            assert_eq!(m.faces[*name].len(), n * layers, "{name}"); // n/2 cells on each of two cube faces
            for &v in &m.node_sets[*name] {
                assert!((m.nodes[v][k] - centre[k]).abs() < 1e-12, "{name}");
            }
            for q in &m.faces[*name] {
                let x = q.map(|v| m.nodes[v]);
                assert!(
                    cross(sub(x[1], x[0]), sub(x[3], x[0]))[k] < 0.0,
                    "`{name}` points inwards"
                );
            }
        }
        let whole = sphere_shell(centre, [0.8, 1.0], (n, layers), ShellPart::Whole);
        assert_eq!(whole.faces.len(), 2, "a whole shell has no flat faces");
    }

    #[test]
    fn the_hemisphere_is_the_lower_half_of_the_whole_shell() {
        let whole = sphere_shell([0.0; 3], [0.5, 1.0], (4, 1), ShellPart::Whole);
        let half = hemisphere_shell([0.0; 3], [0.5, 1.0], 4, 1);
        assert_eq!(2 * half.hexes.len(), whole.hexes.len());
        assert!((2.0 * half.volume() - whole.volume()).abs() < 1e-12);
    }
}
