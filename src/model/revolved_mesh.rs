//! Structured hexahedral mesh of a quarter of a body of revolution: the section
//! `r₀ ≤ r ≤ R`, `z₀ ≤ z ≤ z₁` (a plane rectangle, its radial and axial node coordinates
//! given) turned about the `z` axis from the plane `y = 0` to the plane `x = 0`. It is the 3D
//! model of an axisymmetric section (`scene::revolve`), with its two symmetry planes.
//!
//! - A hollow section (`r₀ > 0`): each radial node line becomes `around` arcs, every node at
//!   `(r cos θ, r sin θ, z)` — the section's nodes on each of the `around + 1` meridians.
//! - A full section (`r₀ = 0`): a "butterfly". The core is the square `[0, s]²`, `s` the
//!   section's radial node nearest `core · R`, on the tensor grid of the section's radial
//!   coordinates up to `s`; outside it, layer `i` blends the square's boundary `S` into the
//!   circle `R S/|S|` by `w = (rᵢ − s)/(R − s)`. On both symmetry planes the nodes are the
//!   section's nodes; the outer surface is the exact circle at its nodes; no cell is
//!   degenerate at the axis.
//!
//! Node sets and faces: `ymin` (the plane `y = 0`), `xmin` (the plane `x = 0`), `zmin`,
//! `zmax`, `outer` (`r = R`), `inner` (`r = r₀`, hollow sections), the node set `axis` (full
//! sections) and `all`.

use super::box_mesh::BoxMesh;
use super::hex_boundary::{boundary_quads, face_node_sets};
use std::collections::BTreeMap;

/// The quarter mesh of the section with radial node coordinates `r` (increasing, `r[0] ≥ 0`)
/// and axial ones `z` (increasing); `around` cells per quarter for a hollow section, `core`
/// the share of the radius of a full section's core square.
pub fn quarter_revolution(r: &[f64], z: &[f64], around: usize, core: f64) -> BoxMesh {
    revolution(r, z, (around, 1), core)
}

/// As [`quarter_revolution`], turned through `quarters` (1, 2 or 4) quarters of a turn: a
/// hollow section only beyond one (the whole turn closes on itself, no seam).
pub fn revolution(r: &[f64], z: &[f64], (around, quarters): (usize, usize), core: f64) -> BoxMesh {
    let (plane, cells) = if r[0] > 0.0 {
        annulus(r, around.max(1), quarters.clamp(1, 4))
    } else {
        butterfly(r, core)
    };
    let s = plane.len();
    let nodes: Vec<[f64; 3]> = z
        .iter()
        .flat_map(|&zk| plane.iter().map(move |p| [p[0], p[1], zk]))
        .collect();
    let mut hexes = Vec::with_capacity(cells.len() * (z.len() - 1));
    for k in 0..z.len() - 1 {
        for c in &cells {
            let [a, b, cc, d] = c.map(|v| v + k * s);
            hexes.push([a, b, cc, d, a + s, b + s, cc + s, d + s]);
        }
    }
    let outer = r[r.len() - 1];
    let tol = 1e-9 * outer.max(z[z.len() - 1].abs()).max(z[0].abs());
    let radius = |p: &[f64; 3]| p[0].hypot(p[1]);
    // the first side a boundary quadrilateral lies on names its face
    let side = |p: &[f64; 3]| -> [bool; 6] {
        [
            p[1].abs() <= tol,
            p[0].abs() <= tol,
            (p[2] - z[0]).abs() <= tol,
            (p[2] - z[z.len() - 1]).abs() <= tol,
            (radius(p) - outer).abs() <= tol,
            (radius(p) - r[0]).abs() <= tol,
        ]
    };
    const NAMES: [&str; 6] = ["ymin", "xmin", "zmin", "zmax", "outer", "inner"];
    let mut faces: BTreeMap<String, Vec<[usize; 4]>> = BTreeMap::new();
    for f in boundary_quads(&hexes) {
        let on = f.map(|v| side(&nodes[v]));
        if let Some(k) = (0..6).find(|&k| on.iter().all(|s| s[k])) {
            faces.entry(NAMES[k].to_string()).or_default().push(f);
        }
    }
    let mut node_sets = face_node_sets(&faces);
    if r[0] == 0.0 {
        node_sets.insert(
            "axis".into(),
            (0..nodes.len()).filter(|&v| radius(&nodes[v]) <= tol).collect(),
        );
    }
    node_sets.insert("all".into(), (0..nodes.len()).collect());
    BoxMesh {
        nodes,
        hexes,
        node_sets,
        faces,
    }
}

/// The annulus through `quarters` quarter turns, `n` cells each: nodes `(i, a)` at radius
/// `r[i]`, angle `a π/(2 n)` (the whole turn wraps `a` round); cells counter-clockwise seen
/// from `+z`.
fn annulus(r: &[f64], n: usize, quarters: usize) -> (Vec<[f64; 2]>, Vec<[usize; 4]>) {
    let m = r.len();
    let cells_around = n * quarters;
    let lines = if quarters == 4 { cells_around } else { cells_around + 1 };
    let id = |i: usize, a: usize| (a % lines) * m + i;
    let plane = (0..lines)
        .flat_map(|a| {
            let t = std::f64::consts::FRAC_PI_2 * a as f64 / n as f64;
            let (sin, cos) = if quarters == 4 || a < cells_around {
                t.sin_cos()
            } else {
                [(1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)][quarters - 1]
            };
            r.iter().map(move |ri| [ri * cos, ri * sin])
        })
        .collect();
    let cells = (0..cells_around)
        .flat_map(|a| (0..m - 1).map(move |i| [id(i, a), id(i + 1, a), id(i + 1, a + 1), id(i, a + 1)]))
        .collect();
    (plane, cells)
}

/// The butterfly of a full section (see the module); cells counter-clockwise seen from `+z`.
fn butterfly(r: &[f64], core: f64) -> (Vec<[f64; 2]>, Vec<[usize; 4]>) {
    let nr = r.len() - 1;
    let outer = r[nr];
    let k = (1..nr)
        .min_by(|&a, &b| (r[a] - core * outer).abs().total_cmp(&(r[b] - core * outer).abs()))
        .unwrap_or(1)
        .min(nr.saturating_sub(1))
        .max(1);
    let s = r[k];
    let mut plane: Vec<[f64; 2]> = Vec::new();
    // the core grid (a, b), a fastest
    for b in 0..=k {
        for a in 0..=k {
            plane.push([r[a], r[b]]);
        }
    }
    let core_id = |a: usize, b: usize| b * (k + 1) + a;
    // the square's boundary, p = 0 … 2k from the plane y = 0 to the plane x = 0
    let square = |p: usize| if p <= k { [s, r[p]] } else { [r[2 * k - p], s] };
    let on_square = |p: usize| if p <= k { core_id(k, p) } else { core_id(2 * k - p, k) };
    let first_outer = plane.len();
    for &ri in &r[k + 1..] {
        let w = (ri - s) / (outer - s);
        for p in 0..=2 * k {
            let q = square(p);
            let len = q[0].hypot(q[1]);
            plane.push([
                q[0] + w * (outer * q[0] / len - q[0]),
                q[1] + w * (outer * q[1] / len - q[1]),
            ]);
        }
    }
    let ring = |i: usize, p: usize| {
        if i == k {
            on_square(p)
        } else {
            first_outer + (i - k - 1) * (2 * k + 1) + p
        }
    };
    let mut cells = Vec::with_capacity(k * k + 2 * k * (nr - k));
    for b in 0..k {
        for a in 0..k {
            cells.push([
                core_id(a, b),
                core_id(a + 1, b),
                core_id(a + 1, b + 1),
                core_id(a, b + 1),
            ]);
        }
    }
    for i in k..nr {
        for p in 0..2 * k {
            cells.push([ring(i, p), ring(i + 1, p), ring(i + 1, p + 1), ring(i, p + 1)]);
        }
    }
    (plane, cells)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_section_becomes_a_butterfly_quarter_cylinder_with_its_sets() {
        let r = [0.0, 0.1, 0.25, 0.45, 0.7, 1.0];
        let z = [-1.0, -0.4, 0.0];
        let m = quarter_revolution(&r, &z, 0, 0.5);
        // core k = 3 (r = 0.45): 9 core cells and 2 · 3 · 2 ring cells per layer
        assert_eq!(m.hexes.len(), (9 + 12) * 2);
        let quarter = std::f64::consts::FRAC_PI_4 * 1.0;
        let v = m.volume();
        assert!(v < quarter && v > 0.97 * quarter, "{v} against {quarter}");
        for &n in &m.node_sets["outer"] {
            assert!((m.nodes[n][0].hypot(m.nodes[n][1]) - 1.0).abs() < 1e-12);
        }
        // the symmetry planes carry the section's nodes, 6 radii at 3 levels each
        assert_eq!(m.node_sets["ymin"].len(), 18);
        assert_eq!(m.node_sets["xmin"].len(), 18);
        assert_eq!(m.node_sets["axis"].len(), 3);
        assert_eq!(m.faces["zmax"].len(), 21);
        assert_eq!(m.faces["outer"].len(), 6 * 2);
    }

    #[test]
    fn a_hollow_section_becomes_a_quarter_annulus() {
        let m = quarter_revolution(&[0.5, 0.75, 1.0], &[0.0, 1.0], 4, 0.5);
        assert_eq!(m.hexes.len(), 8);
        let exact = std::f64::consts::FRAC_PI_4 * (1.0 - 0.25);
        let v = m.volume();
        assert!(v < exact && v > 0.95 * exact, "{v} against {exact}");
        assert_eq!(m.faces["inner"].len(), 4);
        assert_eq!(m.faces["ymin"].len(), 2);
        assert!(!m.node_sets.contains_key("axis"));
    }

    #[test]
    fn a_hollow_section_turns_through_a_half_and_a_whole_turn() {
        let half = revolution(&[0.5, 1.0], &[0.0, 1.0], (3, 2), 0.5);
        assert_eq!((half.hexes.len(), half.nodes.len()), (6, 2 * 2 * 7));
        // both ends lie on the plane y = 0: one face, two quadrilaterals
        assert_eq!(half.faces["ymin"].len(), 2);
        assert!(!half.faces.contains_key("xmin"));
        let whole = revolution(&[0.5, 1.0], &[0.0, 1.0], (3, 4), 0.5);
        assert_eq!((whole.hexes.len(), whole.nodes.len()), (12, 2 * 2 * 12));
        assert!(!whole.faces.contains_key("ymin") && whole.faces["outer"].len() == 12);
        let exact = std::f64::consts::PI * (1.0 - 0.25);
        let v = whole.volume();
        assert!(v < exact && v > 0.9 * exact, "{v} against {exact}");
    }
}
