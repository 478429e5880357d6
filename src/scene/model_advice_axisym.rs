//! Which smaller model a 3D scene would do with, continued: a quarter model of a body of
//! revolution about `z`, loaded and held alike about that axis, is an axisymmetric model of
//! its section (`contrail check`; the plane models: [`super::model_advice`]).
//!
//! The rules read the built model:
//! - **a quarter model**: nodes in `x ≥ 0, y ≥ 0`, with nodes on both planes `x = 0` and
//!   `y = 0`, held there at zero normal to the plane (the symmetry conditions), nothing else
//!   held along `x` or `y`;
//! - **a body of revolution**: the section on `y = 0` (the points `(x, z)`) and the section on
//!   `x = 0` (the points `(y, z)`) are the same, and at every level `z` no node lies farther
//!   from the axis than the section's outermost node there (a box's corners do);
//! - **nothing about the axis**: no load across it (only along `z`), rigid planes normal to
//!   `z` and spheres centred on it, moving along `z` only (contact between deformable bodies
//!   is not judged: such a scene gets no advice);
//! - **held alike about the axis**: a node held along `z` has every node of its ring (same
//!   radius and level) held alike.
//!
//! The advice gives the axisymmetric model's DOFs as two per node of the section `y = 0`.

use crate::model::{Model, Ramp, RigidSurfaceShape, Solid, SurfaceMaster};
use std::collections::{BTreeMap, BTreeSet};

/// What an axisymmetric model of a 3D quarter model would be.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisymmetricAdvice {
    pub dofs_3d: usize,
    pub dofs_axisymmetric: usize,
}

impl AxisymmetricAdvice {
    /// One line for `contrail check`.
    pub fn line(&self) -> String {
        format!(
            "advice: this scene is the quarter of a body of revolution about z, loaded and held alike about that axis: an axisymmetric model of its section (the plane y = 0) would do, with about {} DOFs instead of {} ({:.0}× fewer)",
            self.dofs_axisymmetric,
            self.dofs_3d,
            self.dofs_3d as f64 / self.dofs_axisymmetric.max(1) as f64
        )
    }
}

/// The axisymmetric model a 3D quarter model would do with, if any (see the module).
pub fn axisymmetric_advice(m: &Model<Solid>) -> Option<AxisymmetricAdvice> {
    let size = m.nodes.iter().flatten().fold(0.0f64, |a, c| a.max(c.abs()));
    if m.nodes.is_empty() || size == 0.0 {
        return None;
    }
    let tol = 1e-9 * size;
    let q = |v: f64| (v / tol).round() as i64;
    if m.nodes.iter().any(|p| p[0] < -tol || p[1] < -tol) {
        return None;
    }
    let on = |a: usize| (0..m.nodes.len()).filter(move |&i| m.nodes[i][a].abs() <= tol);
    // the two symmetry sections, as (distance from the axis, level)
    let section = |a: usize| {
        on(a)
            .map(|i| (q(m.nodes[i][1 - a]), q(m.nodes[i][2])))
            .collect::<BTreeSet<_>>()
    };
    let (on_y0, on_x0) = (section(1), section(0));
    if on_y0.is_empty() || on_y0 != on_x0 {
        return None;
    }
    let mut outer: BTreeMap<i64, i64> = BTreeMap::new();
    for (r, z) in &on_y0 {
        let o = outer.entry(*z).or_insert(*r);
        *o = (*o).max(*r);
    }
    let radius = |p: &[f64; 3]| q(p[0].hypot(p[1]));
    let inside = m
        .nodes
        .iter()
        .all(|p| outer.get(&q(p[2])).is_some_and(|o| radius(p) <= *o + 1));
    if !inside || !symmetry_holds_only(m, tol) || !axisymmetric_actions(m) || !rings_held_alike(m, q) {
        return None;
    }
    Some(AxisymmetricAdvice {
        dofs_3d: m.dof_count(),
        dofs_axisymmetric: 2 * on(1).count(),
    })
}

/// `x` held (at zero) exactly on the plane `x = 0` and `y` on `y = 0`, both planes held.
fn symmetry_holds_only(m: &Model<Solid>, tol: f64) -> bool {
    let mut held = [BTreeSet::new(), BTreeSet::new()];
    for p in &m.prescribed {
        let (node, c) = (p.dof / 3, p.dof % 3);
        if c < 2 {
            if !p.is_zero() || m.nodes[node][c].abs() > tol {
                return false;
            }
            held[c].insert(node);
        }
    }
    (0..2).all(|c| {
        let plane: BTreeSet<usize> = (0..m.nodes.len()).filter(|&i| m.nodes[i][c].abs() <= tol).collect();
        held[c] == plane
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
}
