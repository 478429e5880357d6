//! The `[[pressure]]` load: a dead normal traction on a named face of a body, as consistent
//! nodal forces in the body's model.
//!
//! On a face segment `a → b` (reference configuration, listed counter-clockwise around the
//! body, so the outward normal is the tangent turned −90°: `n = (Δy, −Δx)/L`) a pressure `p`
//! (positive: pushing into the body) is the traction `−p n`. Its consistent nodal forces
//! are `f_I = ∫ N_I (−p n) dA` with `dA = ds` (plane strain, per unit thickness), `t ds`
//! (plane stress) or `2π r ds` (axisymmetric: the total over the full circle, like the
//! element's forces), integrated exactly for `r` linear along the segment:
//!
//! * planar: `f_a = f_b = ½ w p (−Δy, Δx)`, `w` = 1 or `t`;
//! * axisymmetric: `f_a = 2π (r_a/3 + r_b/6) p (−Δy, Δx)`, `f_b = 2π (r_a/6 + r_b/3) p (−Δy, Δx)`.
//!
//! The load is dead (it keeps its reference direction and size: no follower terms), which
//! is the small-displacement pressure of the Lamé problem and of most verification cases.

use super::build::{body_index, ramp, Ctx};
use super::types::{RampSpec, SceneFile};
use super::SceneError;
use crate::element::quad::Kinematics;
use crate::model::{Model, NodalLoad};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A dead pressure on a face of a deformable body.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PressureSpec {
    /// Name, unique among the pressures: `--set pressure.NAME.value=…`.
    pub name: Option<String>,
    pub body: String,
    /// A face of the body (`bottom`, `right`, `top`, `left` of a rectangle; `inner`, `outer`,
    /// `start`, `end` of an annulus; a physical curve of a Gmsh mesh).
    pub face: String,
    /// Pressure (force per unit reference area; positive pushes into the body) as a history.
    pub value: RampSpec,
}

/// Consistent nodal forces `[f_a, f_b]` of a unit pressure on the reference segment `a → b`
/// of a face (module docs).
pub fn segment_forces(a: [f64; 2], b: [f64; 2], kinematics: Kinematics) -> [[f64; 2]; 2] {
    let dir = [-(b[1] - a[1]), b[0] - a[0]];
    let (wa, wb) = match kinematics {
        Kinematics::PlaneStrain => (0.5, 0.5),
        Kinematics::PlaneStress { thickness } => (0.5 * thickness, 0.5 * thickness),
        Kinematics::Axisymmetric => {
            let tau = 2.0 * std::f64::consts::PI;
            (tau * (a[0] / 3.0 + b[0] / 6.0), tau * (a[0] / 6.0 + b[0] / 3.0))
        }
    };
    [[wa * dir[0], wa * dir[1]], [wb * dir[0], wb * dir[1]]]
}

/// The nodal loads of the scene's pressures.
pub(super) fn add_pressures(cx: &Ctx, s: &SceneFile, m: &mut Model, end: f64) -> Result<(), SceneError> {
    for ps in &s.pressures {
        let bi = body_index(cx, m, &ps.body)?;
        let body = &m.bodies[bi];
        let Some(segments) = body.faces.get(&ps.face) else {
            let known: Vec<&str> = body.faces.keys().map(|s| s.as_str()).collect();
            return Err(cx.err(
                &ps.face,
                format!("pressure on `{}`: the body has no face `{}`", ps.body, ps.face),
                &format!("its faces are: {}", known.join(", ")),
            ));
        };
        let mut total = BTreeMap::<usize, f64>::new();
        for &[a, b] in segments {
            let f = segment_forces(m.nodes[a], m.nodes[b], body.kinematics);
            for (n, fi) in [a, b].into_iter().zip(f) {
                for (c, v) in fi.into_iter().enumerate() {
                    *total.entry(2 * n + c).or_default() += v;
                }
            }
        }
        let history = ramp(&ps.value, end);
        for (dof, value) in total.into_iter().filter(|(_, v)| *v != 0.0) {
            let mut r = history.clone();
            r.knots.iter_mut().for_each(|k| k.1 *= value);
            m.loads.push(NodalLoad { dof, ramp: r });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_pressure_on_a_ring_face_is_its_area() {
        // the inner face r = 2, 0 ≤ z ≤ 3, listed downwards (counter-clockwise around the
        // body to its right): radial force 2π · 2 · 3 outwards, nothing along z
        let f = segment_forces([2.0, 3.0], [2.0, 0.0], Kinematics::Axisymmetric);
        let tau = 2.0 * std::f64::consts::PI;
        assert!((f[0][0] + f[1][0] - tau * 6.0).abs() < 1e-12 && f[0][1] == 0.0 && f[1][1] == 0.0);
        // an annular end face z = 0 from r = 1 to r = 3 (bottom, listed outwards): area
        // π (3² − 1²) = 8π pushed upwards, the outer node carrying more
        let f = segment_forces([1.0, 0.0], [3.0, 0.0], Kinematics::Axisymmetric);
        assert!((f[0][1] + f[1][1] - 8.0 * std::f64::consts::PI).abs() < 1e-12);
        assert!(f[1][1] > f[0][1]);
        // planar: half each, times the thickness
        let f = segment_forces([0.0, 0.0], [2.0, 0.0], Kinematics::PlaneStress { thickness: 0.1 });
        assert!((f[0][1] - 0.1).abs() < 1e-15 && (f[1][1] - 0.1).abs() < 1e-15);
    }
}
