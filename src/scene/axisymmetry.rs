//! What an axisymmetric model cannot hold: a load or motion that breaks the symmetry about
//! the axis is refused with the reason, before any solve.
//!
//! An axisymmetric body is the revolution of its section about `x = r = 0`; every field of it
//! is the same in each meridian plane. A rigid outline that reaches the axis is revolved into
//! one closed surface (a sphere's cap, a punch's face): moving it along `x` moves that surface
//! sideways, towards one meridian and away from the opposite one — a motion the section cannot
//! represent (it would be read as the cap's radius growing on every side at once). A dead body
//! load with a radial component (`b_r ≠ 0`) cannot come from a uniform field such as gravity,
//! which is radial nowhere but across the axis: gravity along `x` is a sideways load. Both ask
//! for a 3D model (or a plane one turned so that the load is in its plane).

use super::build::Ctx;
use super::types::SceneFile;
use super::SceneError;
use crate::element::quad::Kinematics;
use crate::model::{Model, Piece, RigidShape};
use std::f64::consts::PI;

/// Refuse the symmetry-breaking loads and motions of an axisymmetric scene (see the module).
pub(super) fn refuse_asymmetry(cx: &Ctx, s: &SceneFile, m: &Model) -> Result<(), SceneError> {
    if !m.bodies.iter().any(|b| b.kinematics == Kinematics::Axisymmetric) {
        return Ok(());
    }
    let size = m.nodes.iter().fold(0.0f64, |a, p| a.max(p[0].abs()).max(p[1].abs()));
    let on_axis = super::body_model::AXIS_TOLERANCE * size.max(f64::MIN_POSITIVE);
    for r in &m.rigid {
        let moves_sideways = !r.motion[0].is_zero();
        let reach = least_x(&r.shape);
        if moves_sideways && reach <= on_axis {
            return Err(cx.err(
                &r.name,
                format!(
                    "rigid `{}` reaches the axis of an axisymmetric scene (its outline goes to x = {reach:.4}) and moves along x: revolved, it is one closed surface, and an x motion moves it sideways, which breaks the symmetry about the axis",
                    r.name
                ),
                "remove its `move.x` (an axisymmetric motion is along the axis, y), or model the scene in 3D",
            ));
        }
    }
    for l in &s.body_loads {
        if l.force[0] != 0.0 {
            return Err(cx.err(
                &l.body,
                format!(
                    "body load on `{}` has a radial component {} in an axisymmetric scene: a uniform load across the axis (gravity along x) is sideways, not radial, and breaks the symmetry",
                    l.body, l.force[0]
                ),
                "set force = [0.0, by] (a load along the axis), or model the scene in 3D",
            ));
        }
    }
    Ok(())
}

/// The least `x` of a rigid body's reference outline.
fn least_x(shape: &RigidShape) -> f64 {
    match shape {
        RigidShape::Point { at } => at[0],
        RigidShape::Surface { pieces } => pieces
            .iter()
            .map(|p| match p {
                Piece::Segment { a, b } => a[0].min(b[0]),
                Piece::Arc {
                    centre,
                    radius,
                    theta0,
                    theta1,
                } => {
                    let ends = (centre[0] + radius * theta0.cos()).min(centre[0] + radius * theta1.cos());
                    // the arc passes θ = π (mod 2π), where x is least, if some π + 2kπ lies between its ends
                    let (lo, hi) = (theta0.min(*theta1), theta0.max(*theta1));
                    let k = ((lo - PI) / (2.0 * PI)).ceil();
                    let passes = PI + 2.0 * PI * k <= hi;
                    if passes {
                        centre[0] - radius
                    } else {
                        ends
                    }
                }
            })
            .fold(f64::INFINITY, f64::min),
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::{build, parse, SceneSource};

    fn built_with(extra: &str, sets: &[&str]) -> Result<(), String> {
        let mut src = SceneSource::resolve("hertz-axisym").unwrap();
        src.text.push_str(extra);
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let scene = parse(&src, &sets).map_err(|e| e.to_string())?;
        build(&src, &scene).map(|_| ()).map_err(|e| e.to_string())
    }

    fn built(sets: &[&str]) -> Result<(), String> {
        built_with("", sets)
    }

    #[test]
    fn a_cap_over_the_axis_may_move_along_it_but_not_sideways() {
        built(&[]).expect("the built-in scene");
        let e = built(&["rigid.sphere.move.x=0.01"]).unwrap_err();
        assert!(e.contains("breaks the symmetry") && e.contains("move.x"), "{e}");
    }

    #[test]
    fn an_outline_off_the_axis_may_move_radially() {
        // the sphere's section moved off the axis: a ring whose radius grows is axisymmetric
        let arc = "rigid.sphere.arc={ centre = [2.0, 1.0], radius = 1.0, from_deg = -100.0, to_deg = -60.0 }";
        built(&[arc, "rigid.sphere.move.x=0.01", "rigid.sphere.move.y=0.0"]).expect("a radial ring motion");
    }

    #[test]
    fn the_least_x_of_an_arc_is_exact() {
        use crate::model::{Piece, RigidShape};
        let arc = |theta0: f64, theta1: f64| RigidShape::Surface {
            pieces: vec![Piece::Arc {
                centre: [2.0, 0.0],
                radius: 1.0,
                theta0,
                theta1,
            }],
        };
        let d = std::f64::consts::PI / 180.0;
        assert!((super::least_x(&arc(-100.0 * d, -60.0 * d)) - (2.0 + (100.0 * d).cos())).abs() < 1e-15);
        assert_eq!(super::least_x(&arc(90.0 * d, 270.0 * d)), 1.0, "through θ = π");
        assert_eq!(super::least_x(&arc(-200.0 * d, -150.0 * d)), 1.0, "through θ = −π");
        assert!((super::least_x(&arc(30.0 * d, 60.0 * d)) - (2.0 + (60.0 * d).cos())).abs() < 1e-15);
    }

    #[test]
    fn a_sideways_body_load_is_refused() {
        let load = |f: &str| format!("\n[[body_load]]\nbody = \"block\"\nforce = {f}\n");
        built_with(&load("[0.0, -1.0]"), &[]).expect("a load along the axis");
        let e = built_with(&load("[1.0, 0.0]"), &[]).unwrap_err();
        assert!(e.contains("radial component") && e.contains("force = [0.0, by]"), "{e}");
    }
}
