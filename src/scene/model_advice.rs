//! Which smaller model a 3D scene would do with (`contrail check`): a scene that is the
//! extrusion of a section along one axis, loaded and held the same along it, is a plane model
//! of that section — plane strain when both ends are held along the axis, plane stress when
//! the body is thin and its faces free.
//!
//! The rules read the built model, not the scene's words: along axis `k`,
//! - **extruded**: every column of nodes (of one body, the same other two coordinates) has a
//!   node at each of the same levels along `k`;
//! - **nothing along k**: no load, prescribed motion, rigid plane normal or rigid motion has a
//!   `k` component, and there is no rigid sphere (a sphere is no extrusion);
//! - **the same along k**: every prescribed component (other than `k`) of a node is
//!   prescribed alike at every node of its column, and a loaded one loaded at every node of
//!   it (a load is split by tributary lengths, so its share is not compared);
//! - **plane strain**: every node on both end faces is held at zero along `k`, nothing else;
//!   **plane stress**: nothing held along `k`, or every node of one end face at zero (the
//!   mid-plane of half a plate), and the plate no thicker than a tenth of its least other
//!   extent;
//! - nodes held still in every component (a held body standing for a rigid one) are left out
//!   of the holds along `k`.
//!
//! The advice gives the plane model's degrees of freedom (two per column) against the 3D
//! model's. It is advice: a scene that passes it may still want 3D (a load that the rules do
//! not see, a result through the thickness), and one that fails it is not told anything.

use crate::model::{Model, Ramp, RigidSurfaceShape, Solid, SurfaceMaster};
use std::collections::BTreeMap;

/// A thin body: thickness over the least other extent.
const THIN: f64 = 0.1;

/// What a plane model of a 3D scene would be, and what it would save.
#[derive(Debug, Clone, PartialEq)]
pub struct PlaneAdvice {
    /// The axis of extrusion (0, 1, 2: x, y, z).
    pub axis: usize,
    /// `plane-strain` or `plane-stress`.
    pub model: &'static str,
    /// The plate's thickness (plane stress) or the extruded length (plane strain).
    pub thickness: f64,
    pub dofs_3d: usize,
    pub dofs_plane: usize,
}

impl PlaneAdvice {
    /// One line for `contrail check`.
    pub fn line(&self) -> String {
        let axis = ["x", "y", "z"][self.axis];
        let what = match self.model {
            "plane-strain" => format!("held at u_{axis} = 0 on both ends"),
            _ => format!(
                "a thin plate ({:.3e} thick; whole or its half held on the mid-plane) free along {axis}",
                self.thickness
            ),
        };
        format!(
            "advice: this scene is the extrusion of a section along {axis}, loaded and held alike along it and {what}: a {} model of the section would do, with about {} DOFs instead of {} ({:.0}× fewer)",
            self.model,
            self.dofs_plane,
            self.dofs_3d,
            self.dofs_3d as f64 / self.dofs_plane.max(1) as f64
        )
    }
}

/// The plane model a 3D scene would do with, if any (see the module).
pub fn plane_advice(m: &Model<Solid>) -> Option<PlaneAdvice> {
    (0..3).find_map(|k| advice_along(m, k))
}

fn advice_along(m: &Model<Solid>, k: usize) -> Option<PlaneAdvice> {
    if m.nodes.is_empty() {
        return None;
    }
    let size = (0..3).map(|a| extent(m, a).1 - extent(m, a).0).fold(0.0, f64::max);
    let tol = 1e-9 * size.max(f64::MIN_POSITIVE);
    let columns = extruded_columns(m, k, tol)?;
    // a turned node set moves each node its own way: not a plane model's load
    let turned = m.prescribed.iter().any(|p| p.turn.is_some());
    if turned || !rigid_surfaces_extruded(m, k) || m.loads.iter().any(|l| l.dof % 3 == k && !l.ramp.is_zero()) {
        return None;
    }
    // per node and component: the prescribed ramp (`None` free)
    let mut held: Vec<[Option<&Ramp>; 3]> = vec![[None; 3]; m.nodes.len()];
    for p in &m.prescribed {
        held[p.dof / 3][p.dof % 3] = Some(&p.ramp);
    }
    if !alike_in_columns(m, k, &columns, &held) {
        return None;
    }
    let (model, thickness) = plane_model(m, k, tol, &held)?;
    Some(PlaneAdvice {
        axis: k,
        model,
        thickness,
        dofs_3d: m.dof_count(),
        dofs_plane: 2 * columns.len(),
    })
}

/// Columns of nodes by (body, the two coordinates across the axis, in units of the tolerance).
type Columns = BTreeMap<(Option<usize>, i64, i64), Vec<usize>>;

/// The least and greatest coordinate `a` of the model's nodes.
fn extent(m: &Model<Solid>, a: usize) -> (f64, f64) {
    (m.nodes.iter()).fold((f64::MAX, f64::MIN), |(l, h), p| (l.min(p[a]), h.max(p[a])))
}

/// The columns along `k` — the nodes of one body with the same other two coordinates (two
/// bodies may touch at a node position) — when every column has a node at each of the same
/// levels along `k` (`None` otherwise).
fn extruded_columns(m: &Model<Solid>, k: usize, tol: f64) -> Option<Columns> {
    let body_of = |i: usize| (m.bodies.iter()).position(|b| (b.first_node..b.first_node + b.node_count).contains(&i));
    let key = |i: usize| {
        let q: Vec<i64> = (0..3)
            .filter(|a| *a != k)
            .map(|a| (m.nodes[i][a] / tol).round() as i64)
            .collect();
        (body_of(i), q[0], q[1])
    };
    let mut columns = Columns::new();
    for i in 0..m.nodes.len() {
        columns.entry(key(i)).or_default().push(i);
    }
    let levels = |c: &Vec<usize>| {
        let mut l: Vec<i64> = c.iter().map(|&i| (m.nodes[i][k] / tol).round() as i64).collect();
        l.sort_unstable();
        l
    };
    let first = levels(columns.values().next()?);
    (first.len() >= 2 && columns.values().all(|c| levels(c) == first)).then_some(columns)
}

/// Every column held alike in the components across `k`, and loaded at all its nodes or at
/// none (a load is split over a column by the nodes' tributary lengths: an end node carries
/// half, so its share is not compared).
fn alike_in_columns(m: &Model<Solid>, k: usize, columns: &Columns, held: &[[Option<&Ramp>; 3]]) -> bool {
    let mut loaded = vec![[false; 3]; m.nodes.len()];
    for l in &m.loads {
        loaded[l.dof / 3][l.dof % 3] = true;
    }
    let others = || (0..3).filter(|a| *a != k);
    let held_alike = |c: &Vec<usize>| others().all(|a| c.iter().all(|&i| held[i][a] == held[c[0]][a]));
    let loaded_alike = |c: &Vec<usize>| others().all(|a| c.iter().all(|&i| loaded[i][a] == loaded[c[0]][a]));
    columns.values().all(|c| held_alike(c) && loaded_alike(c))
}

/// The plane model the holds along `k` make, with its thickness: plane strain when both end
/// faces and nothing else are held at zero along `k`; plane stress for a thin plate with
/// nothing held along `k`, or half of one held on its mid-plane (one end face). Nodes held
/// still in every component are a held (rigid) body's and say nothing of the model.
fn plane_model(m: &Model<Solid>, k: usize, tol: f64, held: &[[Option<&Ramp>; 3]]) -> Option<(&'static str, f64)> {
    let n = m.nodes.len();
    let (lo, hi) = extent(m, k);
    let still = |i: usize| held[i].iter().all(|h| h.is_some_and(|r| r.is_zero()));
    let held_k: Vec<usize> = (0..n).filter(|&i| held[i][k].is_some() && !still(i)).collect();
    if held_k.iter().any(|&i| held[i][k].is_some_and(|r| !r.is_zero())) {
        return None;
    }
    let on = |level: f64| {
        (0..n)
            .filter(|&i| (m.nodes[i][k] - level).abs() <= tol && !still(i))
            .collect::<Vec<_>>()
    };
    let ends: Vec<usize> = (0..n)
        .filter(|&i| !still(i) && ((m.nodes[i][k] - lo).abs() <= tol || (m.nodes[i][k] - hi).abs() <= tol))
        .collect();
    let least_other = (0..3)
        .filter(|a| *a != k)
        .map(|a| extent(m, a).1 - extent(m, a).0)
        .fold(f64::MAX, f64::min);
    let plate = if held_k.is_empty() {
        Some(hi - lo)
    } else if held_k == on(lo) || held_k == on(hi) {
        Some(2.0 * (hi - lo))
    } else {
        None
    };
    match plate {
        _ if held_k == ends => Some(("plane-strain", hi - lo)),
        Some(t) if t <= THIN * least_other => Some(("plane-stress", t)),
        _ => None,
    }
}

/// Every rigid surface is the same along `k` and moves across it only.
fn rigid_surfaces_extruded(m: &Model<Solid>, k: usize) -> bool {
    m.surface_contacts.iter().all(|pair| match &pair.master {
        SurfaceMaster::Facets { .. } => true,
        SurfaceMaster::Rigid(r) => {
            let shape = match r.shape {
                RigidSurfaceShape::Plane { normal, .. } => normal[k] == 0.0,
                RigidSurfaceShape::Sphere { .. } => false,
                RigidSurfaceShape::Cylinder { axis, .. } => axis[k].abs() == 1.0,
            };
            shape && r.motion[k].is_zero()
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{build_solid::build_solid, parse, SceneSource};

    fn advice(text: &str) -> Option<PlaneAdvice> {
        let src = SceneSource {
            origin: "test.toml".into(),
            text: text.into(),
        };
        let scene = parse(&src, &[]).unwrap_or_else(|e| panic!("{e}"));
        plane_advice(&build_solid(&src, &scene).unwrap_or_else(|e| panic!("{e}")).model)
    }

    const BLOCK: &str = r#"
name = "slice"
[[body]]
name = "block"
material = { model = "neo-hookean", young = 1000.0, poisson = 0.3 }
mesh = { kind = "box", origin = [0.0, 0.0, 0.0], size = [2.0, 1.0, THICK], elements = [8, 4, NZ] }
[[fix]]
body = "block"
nodes = "ymin"
components = ["x", "y"]
[[load]]
body = "block"
nodes = "ymax"
component = "y"
total = -1.0
"#;

    fn block(thick: &str, nz: &str, extra: &str) -> String {
        BLOCK.replace("THICK", thick).replace("NZ", nz) + extra
    }

    const HELD_ENDS: &str = r#"
[[fix]]
body = "block"
nodes = "zmin"
components = ["z"]
[[fix]]
body = "block"
nodes = "zmax"
components = ["z"]
"#;

    #[test]
    fn a_slice_held_at_both_ends_is_plane_strain() {
        let a = advice(&block("0.5", "2", HELD_ENDS)).expect("plane strain");
        assert_eq!((a.axis, a.model), (2, "plane-strain"));
        assert_eq!(a.dofs_plane, 2 * 9 * 5);
        assert_eq!(a.dofs_3d, 3 * 9 * 5 * 3);
        assert!(
            a.line().contains("4× fewer") || a.line().contains("5× fewer"),
            "{}",
            a.line()
        );
    }

    #[test]
    fn a_thin_free_plate_is_plane_stress_and_a_thick_one_is_nothing() {
        let a = advice(&block("0.05", "1", "")).expect("plane stress");
        assert_eq!((a.axis, a.model), (2, "plane-stress"));
        assert!((a.thickness - 0.05).abs() < 1e-12);
        assert_eq!(advice(&block("0.5", "2", "")), None, "thick and free: 3D");
        // half of a plate 0.05 thick, held on its mid-plane z = 0
        let mid = "\n[[fix]]\nbody = \"block\"\nnodes = \"zmin\"\ncomponents = [\"z\"]\n";
        let half = advice(&block("0.025", "1", mid)).expect("half a plate");
        assert_eq!((half.axis, half.model), (2, "plane-stress"));
        assert!((half.thickness - 0.05).abs() < 1e-12 && half.line().contains("half held on the mid-plane"));
    }

    #[test]
    fn a_load_or_hold_that_varies_along_the_axis_is_not_extruded() {
        let one_end = "\n[[fix]]\nbody = \"block\"\nnodes = \"zmin\"\ncomponents = [\"z\"]\n";
        assert_eq!(advice(&block("0.5", "2", one_end)), None, "one end held");
        let end_load = "\n[[load]]\nbody = \"block\"\nnodes = \"zmax\"\ncomponent = \"x\"\ntotal = 0.1\n";
        assert_eq!(
            advice(&block("0.5", "2", &(HELD_ENDS.to_string() + end_load))),
            None,
            "a load on one end face only"
        );
        let along = "\n[[load]]\nbody = \"block\"\nnodes = \"ymax\"\ncomponent = \"z\"\ntotal = 0.1\n";
        assert_eq!(advice(&block("0.05", "1", along)), None, "a load along the axis");
    }

    #[test]
    fn the_hertz_sphere_is_no_extrusion() {
        let src = SceneSource::resolve("hertz-3d").unwrap();
        let scene = parse(&src, &[]).unwrap();
        assert_eq!(plane_advice(&build_solid(&src, &scene).unwrap().model), None);
    }
}
