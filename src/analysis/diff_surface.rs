//! `contrail diff` of the 3D contact points of two recordings: each slave node of each 3D
//! pair, matched by pair and slave, compared field by field as [`super::diff`] compares the
//! 2D points (facet ids and states exactly, numbers within the tolerance).

use super::diff::{Divergence, FieldDiff, V};
use crate::record::surface_contact::SurfacePointRecord;

/// 3D contact-point fields (`xi1`, `xi2`: the convective coordinates on the facet;
/// `traction1`, `traction2`: the covariant tangential traction after the return map).
pub const SURFACE_FIELDS: &[&str] = &[
    "facet",
    "state",
    "xi1",
    "xi2",
    "gap",
    "normal_force",
    "traction1",
    "traction2",
];

/// The value of `field` at point `p`.
pub(super) fn value(field: &str, p: &SurfacePointRecord) -> V {
    match field {
        "facet" => V::Exact(p.facet.map_or("none".into(), |s| s.to_string())),
        "state" => V::Exact(format!("{:?}", p.state).to_lowercase()),
        "xi1" => V::Num(p.xi[0]),
        "xi2" => V::Num(p.xi[1]),
        "gap" => V::Num(p.gap),
        "normal_force" => V::Num(p.normal_force),
        "traction1" => V::Num(p.traction[0]),
        _ => V::Num(p.traction[1]),
    }
}

/// Compare the points of `pa` with those of `pb` recorded for the same pair and slave, in
/// the fields of `fields` that are [`SURFACE_FIELDS`]; `at` says where (given the point).
pub(super) fn compare(
    pa: &[SurfacePointRecord],
    pb: &[SurfacePointRecord],
    tol: f64,
    fields: &mut [FieldDiff],
    at: &dyn Fn(Option<String>) -> Divergence,
) {
    let by_slave: std::collections::HashMap<(usize, usize), &SurfacePointRecord> =
        pb.iter().map(|q| ((q.pair, q.slave), q)).collect();
    for a in pa {
        let Some(b) = by_slave.get(&(a.pair, a.slave)) else {
            continue;
        };
        let label = || Some(format!("{}/{} (node {})", a.pair_name, a.slave, a.node));
        for fd in fields.iter_mut().filter(|f| SURFACE_FIELDS.contains(&f.field.as_str())) {
            fd.compare(&value(&fd.field, a), &value(&fd.field, b), tol, || at(label()));
        }
    }
}
