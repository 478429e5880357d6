//! How the rerun view draws things: colours, the y-up transform, the traction-arrow scale,
//! the residual that is plotted and which contact points carry a label. Pure functions, so
//! they are tested without a viewer.

use crate::contact::law::ContactState;
use crate::record::ContactPointRecord;

/// rerun's 2D views put +y downward. Every 2D entity of the view lives under one root
/// (`/scene` for the model, `/curve` for the force–displacement curve) that carries this
/// static scale, so positions are logged as they are (hovering shows the true coordinates)
/// and drawn with +y up.
pub const Y_UP_SCALE: [f32; 3] = [1.0, -1.0, 1.0];

/// Where a model point `p` lands on the screen of a 2D view (+y down) once the root
/// transform [`Y_UP_SCALE`] is applied (what the tests check).
#[cfg(test)]
pub fn on_screen(p: [f64; 2]) -> [f64; 2] {
    [p[0] * Y_UP_SCALE[0] as f64, p[1] * Y_UP_SCALE[1] as f64]
}

// Colours that read on both of the viewer's themes (black and white backgrounds, checked
// with `docs/screenshots.sh`): mid-luminance hues, a contrast of about 3:1 or more against
// white and 4.5:1 or more against black. rerun 0.36 draws line strips opaque, an alpha only
// darkening the colour.

/// Reference mesh: grey, drawn as (102, 102, 102) — its alpha darkens it (see above).
pub const REFERENCE: [u8; 4] = [150, 150, 150, 110];
/// Deformed mesh.
pub const MESH: [u8; 4] = [70, 130, 230, 255];
/// Rigid surfaces and points: a saturated violet that reads on dark and light backgrounds.
pub const RIGID: [u8; 4] = [190, 70, 200, 255];
/// Trial tangential traction (thin): dark goldenrod (a light yellow vanishes on white).
pub const TRIAL: [u8; 4] = [184, 134, 11, 255];
/// Returned tangential traction (thick).
pub const RETURNED: [u8; 4] = [230, 45, 45, 255];
/// The force–displacement curve and its current point.
pub const CURVE: [u8; 4] = [70, 130, 230, 255];
/// Axes of the curve view and their labels.
pub const AXES: [u8; 4] = [120, 120, 120, 255];
/// Frame and mid-lines of the curve view (drawn thinner than the axes).
pub const GRID: [u8; 4] = [120, 120, 120, 255];

/// The pressure arrows of a two-pass interface: a dark teal.
pub const PRESSURE: [u8; 4] = [0, 120, 130, 255];

/// Open contact point.
pub const OPEN: [u8; 4] = [140, 140, 140, 255];
/// Closed point of a frictionless pair.
pub const FRICTIONLESS: [u8; 4] = [0, 150, 160, 255];
/// Sticking point.
pub const STICK: [u8; 4] = [30, 155, 60, 255];
/// Slipping point, and the increments with a crossing on the force–displacement curve.
pub const SLIP: [u8; 4] = [225, 105, 0, 255];

/// Colour of a contact point: open grey, stick green, slip orange; a closed point of a
/// frictionless pair (`μ = 0`) is teal — the contact law reports such points as `slip`
/// (the record cannot tell), the view tells them apart by the pair's `μ`.
pub fn point_colour(state: ContactState, mu: f64) -> [u8; 4] {
    match state {
        ContactState::Open => OPEN,
        _ if mu == 0.0 => FRICTIONLESS,
        ContactState::Stick => STICK,
        ContactState::Slip => SLIP,
    }
}

/// Length of a traction arrow at the Coulomb limit, as a fraction of the mesh size.
pub const ARROW_FRACTION: f64 = 0.08;
/// A trial arrow is cut at this multiple of the Coulomb-limit length.
pub const TRIAL_CAP: f64 = 3.0;
/// Arrows start this fraction of the mesh size off the master face, on the slave side.
pub const ARROW_OFFSET_FRACTION: f64 = 0.015;

/// The two tangential traction arrows of a closed contact point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TractionArrows {
    pub origin: [f64; 2],
    pub trial: [f64; 2],
    pub returned: [f64; 2],
}

/// Traction arrows at a fixed scale: an arrow of length `limit_len` is a traction equal to
/// the Coulomb limit `μ N` of the point, so the returned traction of a slipping point is
/// always `limit_len` long and that of a sticking point shorter; the trial traction is drawn
/// on the same scale, cut at [`TRIAL_CAP`] times `limit_len`. Arrows start `offset` off the
/// face along the master normal. None for open points, frictionless pairs and points
/// without a finite normal force, tangent or normal.
pub fn traction_arrows(c: &ContactPointRecord, mu: f64, limit_len: f64, offset: f64) -> Option<TractionArrows> {
    let limit = mu * c.normal_force;
    let finite = |v: [f64; 2]| v.iter().all(|x| x.is_finite());
    let positive = limit > 0.0 && limit.is_finite();
    if c.state == ContactState::Open || !positive || !finite(c.tangent) || !finite(c.normal) || !finite(c.position) {
        return None;
    }
    let scale = limit_len / limit;
    let along = |t: f64, cap: f64| {
        let l = (t * scale).clamp(-cap, cap);
        let l = if l.is_finite() { l } else { 0.0 };
        [l * c.tangent[0], l * c.tangent[1]]
    };
    Some(TractionArrows {
        origin: [
            c.position[0] + offset * c.normal[0],
            c.position[1] + offset * c.normal[1],
        ],
        trial: along(c.trial_traction, TRIAL_CAP * limit_len),
        returned: along(c.traction, limit_len),
    })
}

/// `‖R‖ / F_ref` when the reference force is positive and the ratio finite; None otherwise
/// (a zero reference at the start of a run would divide by zero).
pub fn relative_residual(residual: f64, reference: f64) -> Option<f64> {
    let usable = reference > 0.0 && reference.is_finite() && residual.is_finite();
    if !usable {
        return None;
    }
    let r = residual / reference;
    (r.is_finite() && r > 0.0).then_some(r)
}

/// The label of a contact point, if it carries information: a point that crossed in this
/// increment (`s3→s4`) and a rigid slave point (`C · s15`, `C` when it has no segment).
/// Ordinary node slaves carry none (their colour says their state).
pub fn point_label(c: &ContactPointRecord, crossed_from: Option<usize>) -> Option<String> {
    let seg = c.segment.map(|s| format!("s{s}"));
    let rigid = c.slave_label.strip_prefix("rigid ");
    match (crossed_from, rigid, seg) {
        (Some(a), r, Some(s)) => Some(format!("{}s{a}→{s}", r.map_or(String::new(), |n| format!("{n} · ")))),
        (_, Some(name), Some(s)) => Some(format!("{name} · {s}")),
        (_, Some(name), None) => Some(name.to_string()),
        _ => None,
    }
}

/// The smallest "nice" number (1, 2 or 5 times a power of ten) not below `x` (> 0), used
/// as the extent of an axis of the curve view so that it changes rarely.
pub fn nice_ceiling(x: f64) -> f64 {
    let usable = x > 0.0 && x.is_finite();
    if !usable {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    for m in [1.0, 2.0, 5.0, 10.0] {
        if m * p >= x * (1.0 - 1e-12) {
            return m * p;
        }
    }
    10.0 * p
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(state: ContactState) -> ContactPointRecord {
        ContactPointRecord {
            pair: 0,
            pair_name: "p".into(),
            slave: 0,
            slave_label: "node 3".into(),
            segment: Some(4),
            previous_segment: Some(4),
            xi: 0.0,
            xi_anchor: 0.0,
            gap: -1e-3,
            normal_force: 2.0,
            trial_traction: 1.0,
            traction: 0.5,
            state,
            crossing: false,
            position: [1.0, 2.0],
            contact_point: [1.0, 2.0],
            normal: [0.0, 1.0],
            tangent: [1.0, 0.0],
            multiplier: [f64::NAN; 2],
            force: [0.5, 2.0],
        }
    }

    #[test]
    fn y_up_puts_higher_points_higher_on_screen() {
        // on screen +y is down, so a larger model y must give a smaller screen y
        assert!(on_screen([0.0, 1.0])[1] < on_screen([0.0, 0.0])[1]);
        assert_eq!(on_screen([2.0, 3.0]), [2.0, -3.0]);
    }

    #[test]
    fn arrows_are_scaled_by_the_coulomb_limit_and_offset_from_the_face() {
        let c = point(ContactState::Stick);
        let a = traction_arrows(&c, 0.5, 1.0, 0.1).unwrap();
        // μN = 1: the trial traction 1 is one limit long, the returned 0.5 half of it
        assert_eq!(a.trial, [1.0, 0.0]);
        assert_eq!(a.returned, [0.5, 0.0]);
        assert_eq!(a.origin, [1.0, 2.1]);
    }

    #[test]
    fn a_slipping_point_shows_its_returned_traction_whatever_the_trial() {
        let mut c = point(ContactState::Slip);
        c.trial_traction = -1e5; // a jump of the straightforward transfer
        c.traction = -1.0;
        let a = traction_arrows(&c, 0.5, 2.0, 0.0).unwrap();
        assert_eq!(a.returned, [-2.0, 0.0]);
        assert_eq!(a.trial, [-TRIAL_CAP * 2.0, 0.0]);
    }

    #[test]
    fn no_arrows_for_open_or_frictionless_points() {
        assert!(traction_arrows(&point(ContactState::Open), 0.5, 1.0, 0.0).is_none());
        assert!(traction_arrows(&point(ContactState::Slip), 0.0, 1.0, 0.0).is_none());
        let mut c = point(ContactState::Stick);
        c.tangent = [f64::NAN; 2];
        assert!(traction_arrows(&c, 0.5, 1.0, 0.0).is_none());
    }

    #[test]
    fn frictionless_contact_is_not_coloured_as_slip() {
        assert_ne!(
            point_colour(ContactState::Slip, 0.0),
            point_colour(ContactState::Slip, 0.2)
        );
        assert_eq!(
            point_colour(ContactState::Open, 0.0),
            point_colour(ContactState::Open, 0.2)
        );
    }

    #[test]
    fn no_residual_spike_when_the_reference_is_zero() {
        assert_eq!(relative_residual(1e-3, 0.0), None);
        assert_eq!(relative_residual(0.0, 1.0), None);
        assert_eq!(relative_residual(2.0, 4.0), Some(0.5));
    }

    #[test]
    fn only_crossings_and_rigid_slaves_are_labelled() {
        let mut c = point(ContactState::Stick);
        assert_eq!(point_label(&c, None), None);
        assert_eq!(point_label(&c, Some(3)).as_deref(), Some("s3→s4"));
        c.slave_label = "rigid C".into();
        assert_eq!(point_label(&c, None).as_deref(), Some("C · s4"));
        assert_eq!(point_label(&c, Some(3)).as_deref(), Some("C · s3→s4"));
        c.segment = None;
        assert_eq!(point_label(&c, None).as_deref(), Some("C"));
    }

    #[test]
    fn nice_ceilings() {
        assert_eq!(nice_ceiling(0.7), 1.0);
        assert_eq!(nice_ceiling(1.0), 1.0);
        assert_eq!(nice_ceiling(1.3), 2.0);
        assert_eq!(nice_ceiling(3.0), 5.0);
        assert_eq!(nice_ceiling(11.0), 20.0);
        assert_eq!(nice_ceiling(0.0), 1.0);
        assert_eq!(nice_ceiling(f64::NAN), 1.0);
    }
}
