//! Which smaller model a 3D scene would do with, continued: a body of revolution about `z` —
//! whole, half or a quarter — loaded and held alike about that axis, is an axisymmetric model
//! of its section (`contrail check`; the plane models: [`super::model_advice`]).
//!
//! The rules read the built model:
//! - **the part modelled**: a quarter (nodes in `x ≥ 0, y ≥ 0`), a half (`y ≥ 0` or `x ≥ 0`)
//!   or the whole; each symmetry plane that bounds it held whole at zero normal to itself,
//!   and nothing else held along `x` or `y` but nodes on the axis (at zero: `u_r = 0`);
//! - **a body of revolution**: its sections on the meridian half-planes it spans (`y = 0,
//!   x ≥ 0`; `x = 0, y ≥ 0`; `y = 0, x ≤ 0`; `x = 0, y ≤ 0`) are the same, as points
//!   (distance from the axis, level), and at every level `z` no node lies farther from the
//!   axis than the section's outermost node there (a box's corners do);
//! - **nothing about the axis**: no load across it (only along `z`), rigid planes normal to
//!   `z` and spheres centred on it, moving along `z` only (contact between deformable bodies
//!   is not judged: such a scene gets no advice);
//! - **held alike about the axis**: a node held along `z` has every node of its ring (same
//!   radius and level) held alike.
//!
//! The advice gives the axisymmetric model's DOFs as two per node of the section `y = 0`,
//! `x ≥ 0`. A mesh with no nodes on those half-planes (a cubed sphere's) gets no advice.

use crate::model::{Model, Ramp, RigidSurfaceShape, Solid, SurfaceMaster};
use std::collections::{BTreeMap, BTreeSet};

/// What an axisymmetric model of a 3D model would be.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisymmetricAdvice {
    /// `"the quarter of a"`, `"half a"` or `"a"` (body of revolution).
    pub part: &'static str,
    pub dofs_3d: usize,
    pub dofs_axisymmetric: usize,
}

impl AxisymmetricAdvice {
    /// One line for `contrail check`.
    pub fn line(&self) -> String {
        format!(
            "advice: this scene is {} body of revolution about z, loaded and held alike about that axis: an axisymmetric model of its section (the half-plane y = 0, x ≥ 0) would do, with about {} DOFs instead of {} ({:.0}× fewer)",
            self.part,
            self.dofs_axisymmetric,
            self.dofs_3d,
            self.dofs_3d as f64 / self.dofs_axisymmetric.max(1) as f64
        )
    }
}

/// The meridian half-planes at 0°, 90°, 180° and 270°: a node on one, as (its distance from
/// the axis, its level), or `None`.
fn on_meridian(p: &[f64; 3], k: usize, tol: f64) -> Option<(f64, f64)> {
    let (along, across) = [(p[0], p[1]), (p[1], p[0]), (-p[0], p[1]), (-p[1], p[0])][k];
    (across.abs() <= tol && along >= -tol).then_some((along.max(0.0), p[2]))
}

/// The axisymmetric model a 3D model would do with, if any (see the module).
pub fn axisymmetric_advice(m: &Model<Solid>) -> Option<AxisymmetricAdvice> {
    let size = m.nodes.iter().flatten().fold(0.0f64, |a, c| a.max(c.abs()));
    if m.nodes.is_empty() || size == 0.0 {
        return None;
    }
    let tol = 1e-9 * size;
    let q = |v: f64| (v / tol).round() as i64;
    // which part of the turn the body covers: x ≥ 0 and/or y ≥ 0 where no node lies below
    let below = |c: usize| m.nodes.iter().any(|p| p[c] < -tol);
    let planes: Vec<usize> = (0..2).filter(|&c| !below(c)).collect();
    let (part, meridians): (&'static str, &[usize]) = match (below(0), below(1)) {
        (false, false) => ("the quarter of a", &[0, 1]),
        (true, false) => ("half a", &[0, 1, 2]),
        (false, true) => ("half a", &[3, 0, 1]),
        (true, true) => ("a", &[0, 1, 2, 3]),
    };
    // the sections on the meridians the body spans, as (distance from the axis, level)
    let section = |k: usize| {
        (m.nodes.iter())
            .filter_map(|p| on_meridian(p, k, tol).map(|(r, z)| (q(r), q(z))))
            .collect::<BTreeSet<_>>()
    };
    let first = section(meridians[0]);
    if first.is_empty() || meridians[1..].iter().any(|&k| section(k) != first) {
        return None;
    }
    let mut outer: BTreeMap<i64, i64> = BTreeMap::new();
    for (r, z) in &first {
        let o = outer.entry(*z).or_insert(*r);
        *o = (*o).max(*r);
    }
    let radius = |p: &[f64; 3]| q(p[0].hypot(p[1]));
    let inside = m
        .nodes
        .iter()
        .all(|p| outer.get(&q(p[2])).is_some_and(|o| radius(p) <= *o + 1));
    if !inside || !symmetry_holds_only(m, &planes, tol) || !axisymmetric_actions(m) || !rings_held_alike(m, q) {
        return None;
    }
    let on_section = m.nodes.iter().filter(|p| on_meridian(p, 0, tol).is_some()).count();
    Some(AxisymmetricAdvice {
        part,
        dofs_3d: m.dof_count(),
        dofs_axisymmetric: 2 * on_section,
    })
}

/// `x` and `y` held only at zero, and only on the axis or on the symmetry plane across them
/// (`planes`: `0` for `x = 0`, `1` for `y = 0`), each such plane held whole.
fn symmetry_holds_only(m: &Model<Solid>, planes: &[usize], tol: f64) -> bool {
    let mut held = [BTreeSet::new(), BTreeSet::new()];
    for p in &m.prescribed {
        let (node, c) = (p.dof / 3, p.dof % 3);
        if c < 2 {
            let x = m.nodes[node];
            let on_axis = x[0].hypot(x[1]) <= tol;
            let on_plane = planes.contains(&c) && x[c].abs() <= tol;
            if !p.is_zero() || !(on_axis || on_plane) {
                return false;
            }
            held[c].insert(node);
        }
    }
    planes.iter().all(|&c| {
        (0..m.nodes.len())
            .filter(|&i| m.nodes[i][c].abs() <= tol)
            .all(|i| held[c].contains(&i))
    })
}

/// Loads along `z` only; rigid planes normal to `z`, spheres on the axis and cylinders about
/// it, motions along `z`.
fn axisymmetric_actions(m: &Model<Solid>) -> bool {
    let loads = m.loads.iter().all(|l| l.dof % 3 == 2 || l.ramp.is_zero());
    let rigid = m.surface_contacts.iter().all(|pair| match &pair.master {
        SurfaceMaster::Facets { .. } => false,
        SurfaceMaster::Rigid(r) => {
            let on_axis = match r.shape {
                RigidSurfaceShape::Plane { normal, .. } => normal[0] == 0.0 && normal[1] == 0.0,
                RigidSurfaceShape::Sphere { centre, .. } => centre[0] == 0.0 && centre[1] == 0.0,
                RigidSurfaceShape::Cylinder { point, axis, .. } => {
                    point[0] == 0.0 && point[1] == 0.0 && axis[2].abs() == 1.0
                }
            };
            on_axis && r.motion[0].is_zero() && r.motion[1].is_zero()
        }
    });
    loads && rigid
}

/// Every node held along `z` has its whole ring held alike (same radius and level).
fn rings_held_alike(m: &Model<Solid>, q: impl Fn(f64) -> i64) -> bool {
    let mut rings: BTreeMap<(i64, i64), Vec<Option<&Ramp>>> = BTreeMap::new();
    let mut held_z: Vec<Option<&Ramp>> = vec![None; m.nodes.len()];
    for p in m.prescribed.iter().filter(|p| p.dof % 3 == 2) {
        held_z[p.dof / 3] = Some(&p.ramp);
    }
    for (i, p) in m.nodes.iter().enumerate() {
        rings.entry((q(p[0].hypot(p[1])), q(p[2]))).or_default().push(held_z[i]);
    }
    rings.values().all(|r| r.iter().all(|h| *h == r[0]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{build_solid::build_solid, parse, SceneSource};

    fn advice(path: &str, text: &str) -> Option<AxisymmetricAdvice> {
        let src = SceneSource {
            origin: path.into(),
            text: text.into(),
        };
        let scene = parse(&src, &[]).unwrap_or_else(|e| panic!("{e}"));
        axisymmetric_advice(&build_solid(&src, &scene).unwrap_or_else(|e| panic!("{e}")).model)
    }

    const DISC: &str = include_str!("../../tests/data/disc-3d.toml");
    const DISC_PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/disc-3d.toml");

    #[test]
    fn the_quarter_disc_between_plates_is_axisymmetric() {
        let text = DISC.replace("disc-quarter.msh", "disc-quarter-4.msh");
        let a = advice(DISC_PATH, &text).expect("axisymmetric");
        // the section y = 0 of the 4·4·4 butterfly mesh: 9 nodes across, 5 levels
        assert_eq!(a.dofs_axisymmetric, 2 * 9 * 5);
        assert_eq!(a.dofs_3d, 915);
        assert!(a.line().contains("about 90 DOFs instead of 915"), "{}", a.line());
    }

    #[test]
    fn a_sideways_motion_or_a_box_is_not() {
        let text = DISC.replace("disc-quarter.msh", "disc-quarter-4.msh");
        let sideways = text.replace("move = { z = -0.02 }", "move = { x = 0.01, z = -0.02 }");
        assert_eq!(advice(DISC_PATH, &sideways), None, "a plate moving across the axis");
        let hertz = SceneSource::resolve("hertz-3d").unwrap();
        let scene = parse(&hertz, &[]).unwrap();
        let boxed = axisymmetric_advice(&build_solid(&hertz, &scene).unwrap().model);
        assert_eq!(boxed, None, "a box's corners lie outside its section");
    }

    /// A tube (r 0.5 … 1, height 1) turned through `turn` degrees, its base held along z and
    /// its top pushed down, with `extra` TOML appended.
    fn tube(turn: f64, extra: &str) -> String {
        format!(
            r#"name = "tube"
[[body]]
name = "tube"
material = {{ model = "neo-hookean", young = 1000.0, poisson = 0.3 }}
mesh = {{ kind = "revolved", origin = [0.5, 0.0], size = [0.5, 1.0], elements = [2, 2], around = 3, turn_deg = {turn} }}
[[fix]]
body = "tube"
nodes = "zmin"
components = ["z"]
[[fix]]
body = "tube"
nodes = "zmax"
components = ["z"]
value = -0.01
{extra}"#
        )
    }

    #[test]
    fn a_whole_or_half_tube_held_alike_is_axisymmetric_and_a_sideways_hold_is_not() {
        let whole = advice("tube.toml", &tube(360.0, "")).expect("a whole body of revolution");
        assert_eq!(
            (whole.part, whole.dofs_axisymmetric, whole.dofs_3d),
            ("a", 2 * 3 * 3, 3 * 3 * 3 * 12)
        );
        assert!(
            whole.line().contains("this scene is a body of revolution"),
            "{}",
            whole.line()
        );
        let symmetry = "[[fix]]\nbody = \"tube\"\nnodes = \"ymin\"\ncomponents = [\"y\"]\n";
        let half = advice("tube.toml", &tube(180.0, symmetry)).expect("half a body of revolution");
        assert_eq!(half.part, "half a");
        assert_eq!(
            advice("tube.toml", &tube(180.0, "")),
            None,
            "its symmetry plane is not held"
        );
        let sideways = "[[fix]]\nbody = \"tube\"\nnodes = \"outer\"\ncomponents = [\"x\"]\n";
        assert_eq!(
            advice("tube.toml", &tube(360.0, sideways)),
            None,
            "held across the axis off it"
        );
    }
}
