//! Why an increment may have no solution at all, second case: a contact point that slides
//! onto a node of a faceted master face. A node-to-segment pair on straight segments has
//! no normal at the face's nodes — the two segments' normals differ there — so the contact
//! force jumps as the point's projection passes from one segment to the next, and where the
//! load holds the point at the node the residual has no root: Newton cycles between the two
//! segments at any step (Wriggers, Computational Contact Mechanics (2006) §9.1, the reason
//! for smoothing the master; the seed smooths its master for the same reason). The failure
//! should say so and name the remedy instead of only "no convergence".

use crate::contact::pairing::HELD_EXTENSION;
use crate::model::{Master, Model, Smoothing};
use crate::record::ChangingPoint;

/// The diagnosis of a failed increment whose changing contact points include one at a node
/// of a faceted deformable master (`Smoothing::None`): one sentence to append to the
/// failure's reason, or `None`.
pub fn faceted_node(model: &Model, points: &[ChangingPoint]) -> Option<String> {
    // 3D points (`surface`) index the surface pairs, whose facets this diagnosis is not for
    let p = points.iter().filter(|p| !p.surface).find(|p| {
        let pair = &model.contacts[p.pair];
        let faceted = matches!(pair.master, Master::Face { .. }) && pair.face_smoothing() == Smoothing::None;
        // at the node: within the band about a segment's end where the pairing already holds
        // a point chattering across a kink of the master
        faceted && p.xi.is_finite() && (p.xi.abs() - 1.0).abs() <= HELD_EXTENSION
    })?;
    Some(format!(
        "{} of `{}` sits at a node of its faceted master (ξ = {}), where the face's normal jumps: a node-to-segment contact has no equilibrium there while the point is held at the node, so this may be where the method fails; smooth the master (`master_smoothing = \"hermite\"` or `\"bezier\"` on the contact)",
        p.slave_label,
        p.pair_name,
        crate::format::plain(p.xi)
    ))
}
