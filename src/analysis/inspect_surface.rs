//! What `contrail inspect` says of a recording's 3D (node-to-surface) contact: each pair,
//! its points at the last increment by state, and the points that crossed facet edges.

use super::inspect::PointCrossings;
use super::recording::Recording;
use crate::contact::law::ContactState;
use crate::format::{count, plain, sig};
use crate::record::surface_contact::RigidShapeInfo;

/// One line per 3D pair: its slaves, its master and transfer scheme.
pub fn pair_rows(r: &Recording) -> Vec<String> {
    (r.model.surface_contacts.iter())
        .map(|p| {
            let master = match &p.rigid {
                Some(RigidShapeInfo::Plane { .. }) => format!("{} (plane)", p.master),
                Some(RigidShapeInfo::Sphere { radius, .. }) => {
                    format!("{} (sphere, radius {})", p.master, plain(*radius))
                }
                Some(RigidShapeInfo::Cylinder { radius, .. }) => {
                    format!("{} (cylinder, radius {})", p.master, plain(*radius))
                }
                None => format!("{} ({})", p.master, count(p.master_facets.len(), "facet", "facets")),
            };
            format!(
                "{}: {} against the master {master} ({}, μ = {})",
                p.name,
                count(p.slave_nodes.len(), "slave node", "slave nodes"),
                p.transfer,
                plain(p.mu)
            )
        })
        .collect()
}

/// One line per 3D pair at the last increment with points: how many are closed, by state,
/// the total normal force, and the histories lost over the run.
pub fn state_rows(r: &Recording) -> Vec<String> {
    let Some((&inc, points)) = r.surface.iter().next_back() else {
        return Vec::new();
    };
    (r.model.surface_contacts.iter().enumerate())
        .map(|(ip, p)| {
            let of_pair = || points.iter().filter(move |q| q.pair == ip);
            let state = |s: ContactState| of_pair().filter(|q| q.state == s).count();
            let (stick, slip) = (state(ContactState::Stick), state(ContactState::Slip));
            let force: f64 = of_pair().map(|q| q.normal_force).sum();
            let lost = (r.surface.values().flatten())
                .filter(|q| q.pair == ip && q.history_lost)
                .count();
            format!(
                "{}: {} of {} closed at increment {inc} ({stick} stick, {slip} slip), normal force {}; {} lost",
                p.name,
                stick + slip,
                p.slave_nodes.len(),
                sig(force, 4),
                count(lost, "friction history", "friction histories")
            )
        })
        .collect()
}

/// The 3D points that crossed a facet edge while closed, with the increments they did it
/// in (pairs after the 2D ones: `pair` is offset by the number of 2D pairs).
pub fn crossings_per_point(r: &Recording) -> Vec<PointCrossings> {
    let offset = r.model.contacts.len();
    let mut out: Vec<PointCrossings> = Vec::new();
    for (&inc, points) in &r.surface {
        for q in points.iter().filter(|q| q.crossing) {
            let pair = offset + q.pair;
            let at = match out.iter().position(|p| p.pair == pair && p.slave == q.slave) {
                Some(i) => i,
                None => {
                    out.push(PointCrossings {
                        pair,
                        pair_name: q.pair_name.clone(),
                        slave: q.slave,
                        slave_label: format!("node {}", q.node),
                        crossings: 0,
                        increments: Vec::new(),
                    });
                    out.len() - 1
                }
            };
            out[at].crossings += 1;
            out[at].increments.push(inc);
        }
    }
    out.sort_by_key(|p| (p.pair, p.slave));
    out
}
