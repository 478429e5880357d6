//! One slave point of a 3D pair at an iterate: paired with its master (a facet of a
//! deformable face, a rigid plane or a rigid sphere), its friction history carried onto the
//! facet it is on now, and its kernel evaluated into local arrays ([`PointLocal`]) with the
//! global DOFs they belong to — the system ([`super::system`]) assembles them.

use super::cylinder::CylinderChart;
use super::decision::SurfaceRule;
use super::locate::locate;
use super::master::{facet_point, plane_facet, rigid_point, PointLocal};
use super::nagata::FacetBends;
use super::point::RigidChart;
use super::point::{PointEval, DOFS};
use super::search::{past_free_border, FacetGrid, FREE_BORDER_HOLD, FREE_BORDER_ROUNDOFF};
use super::sphere::SphereChart;
use super::surface::Facet;
use super::system::{Carried, SurfaceConfig, SurfaceHistory, SurfaceNow};
use super::transfer::{transfer, trial_against_continuous, Scheme};
use super::vec3::norm;
use crate::contact::law::ContactState;
use crate::model::{RigidSurfaceShape, SurfaceMaster, SurfacePair};

/// A point as evaluated: its state, the global DOFs of its local arrays, and the
/// magnitudes of the coordinates they were computed from (the round-off weights of the
/// residual criterion).
pub struct Evaluated {
    pub now: SurfaceNow,
    pub dofs: [usize; DOFS],
    pub positions: [f64; DOFS],
}

impl Evaluated {
    fn unpaired() -> Self {
        Evaluated {
            now: SurfaceNow::default(),
            dofs: [0; DOFS],
            positions: [0.0; DOFS],
        }
    }
}

/// Where the search for a slave's facet starts: the facet of the last iterate (else of the
/// last converged increment), whether the point was closed at the last iterate, and the
/// free borders of the master's facets.
pub struct SearchStart<'a> {
    pub grid: Option<&'a FacetGrid>,
    pub facet: Option<usize>,
    pub closed_at_last_iterate: bool,
    pub borders: &'a [[bool; 4]],
    /// The master face's bends where its facets are Nagata patches.
    pub bends: Option<&'a FacetBends>,
}

/// Pair and evaluate slave `is` of `pair`, its state decided by `decider` (the rule and
/// whether it decides by the force unknowns alone); the local arrays into `local`.
pub fn evaluate_point(
    cfg: &SurfaceConfig,
    (pair, is, hist): (&SurfacePair, usize, &SurfaceHistory),
    search: SearchStart,
    plane_half: f64,
    decider: (SurfaceRule, bool),
    local: &mut PointLocal,
) -> Evaluated {
    match &pair.master {
        SurfaceMaster::Facets { facets, .. } => on_facets(cfg, (pair, is, hist), facets, search, decider, local),
        SurfaceMaster::Rigid(rigid) => on_rigid(cfg, (pair, is, hist), rigid, plane_half, decider, local),
    }
}

/// Slave `is` against the facets of a deformable face: located (from `start`), its history
/// carried onto the facet it is on now, evaluated on its 5 nodes. A point whose contact
/// point lies past the face's free border (`borders`) by more than its round-off
/// ([`FREE_BORDER_ROUNDOFF`]) is not paired ([`past_free_border`]), unless it was closed on
/// the face at the last converged increment or at the last iterate (as in 2D,
/// `contact::pairing::held_at_free_end`) and is still penetrating, within
/// [`FREE_BORDER_HOLD`] of the border — on that facet or the next one along the border (a
/// point sliding along the free border crosses facets there). Without the iterate's part, a
/// node of a body flush with its master's border, pressed in, was released as soon as
/// Newton moved it a hair past the border and caught again when it came back: the residual
/// jumped there and Newton stalled on the jump.
fn on_facets(
    cfg: &SurfaceConfig,
    (pair, is, hist): (&SurfacePair, usize, &SurfaceHistory),
    facets: &[[usize; 4]],
    search: SearchStart,
    decider: (SurfaceRule, bool),
    local: &mut PointLocal,
) -> Evaluated {
    let node = pair.slaves[is];
    let origin = cfg.model.nodes[node];
    let mut out = Evaluated::unpaired();
    let grid = search.grid.expect("a facet master has a grid");
    let bends = search.bends;
    let Some(f) = locate(
        cfg,
        (facets, bends),
        grid,
        (node, origin),
        search.facet,
        pair.search_radius,
    ) else {
        return out;
    };
    out.now.facet = Some(f);
    let facet_at = |f: usize| {
        let x = cfg.facet_about(&facets[f], origin);
        Facet {
            x,
            bend: bends.map(|b| b.of(f)),
        }
    };
    let facet_now = facet_at(f);
    let facet_b = facet_now.x;
    let carried = match (hist.history.filter(|_| hist.closed), hist.facet) {
        (Some(h), Some(a)) if a != f => {
            let facet_a = facet_at(a);
            let carried = transfer(pair.transfer, &facet_a, &h, &facet_now).ok();
            out.now.history_lost = carried.is_none();
            if let (Some(to), false) = (carried, pair.transfer == Scheme::Continuous) {
                out.now.trial_jump =
                    trial_against_continuous(&facet_a, &h, &facet_now, &to, pair.law_at(is, cfg.t).eps_t);
            }
            out.now.carried = carried.map(|to| Carried {
                from_facet: a,
                from: h,
                to,
            });
            carried
        }
        (h, _) => h,
    };
    let x_s = cfg.node_about(node, origin);
    let law = pair.law_at(is, cfg.t);
    out.now.frictional = carried.is_some() && law.mu > 0.0;
    let Ok(e) = facet_point(law, (x_s, facet_b, facet_now.bend), carried, decider, local) else {
        out.now.facet = None;
        return out;
    };
    let past = past_free_border(e.projection.point.xi, search.borders[f]);
    let closed_before = (hist.closed && hist.facet.is_some()) || search.closed_at_last_iterate;
    let held = closed_before && e.projection.gap < 0.0 && past <= FREE_BORDER_HOLD;
    if past > FREE_BORDER_ROUNDOFF && !held {
        return Evaluated::unpaired();
    }
    out.now.eval = Some(in_model_coordinates(e, origin));
    let nodes = [node, facets[f][0], facets[f][1], facets[f][2], facets[f][3]];
    out.dofs = std::array::from_fn(|i| 3 * nodes[i / 3] + i % 3);
    let locals = [x_s, facet_b[0], facet_b[1], facet_b[2], facet_b[3]];
    out.positions = std::array::from_fn(|j| locals[j / 3][j % 3].abs());
    out
}

/// Slave `is` against a rigid plane (a fixed facet: the slave's block of the facet kernel),
/// cylinder or sphere (the facet kernel on their charts); evaluated on the slave's 3 DOFs.
fn on_rigid(
    cfg: &SurfaceConfig,
    (pair, is, hist): (&SurfacePair, usize, &SurfaceHistory),
    rigid: &crate::model::RigidSurface,
    plane_half: f64,
    decider: (SurfaceRule, bool),
    local: &mut PointLocal,
) -> Evaluated {
    let node = pair.slaves[is];
    let origin = cfg.model.nodes[node];
    let x_s = cfg.node_about(node, origin);
    let law = pair.law_at(is, cfg.t);
    let mut out = Evaluated::unpaired();
    let offset = rigid.offset(cfg.t);
    // a sphere or a cylinder about the slave's origin, moved
    let about = |p: [f64; 3]| -> [f64; 3] { std::array::from_fn(|c| (p[c] - origin[c]) + offset[c]) };
    let history = hist.history.filter(|_| hist.closed);
    let frictional = history.is_some() && law.mu > 0.0;
    // the kernel on the chart of a sphere or a cylinder, and the scale of its coordinates
    let on_chart = |chart: RigidChart, local: &mut PointLocal| {
        let e = rigid_point(law, x_s, chart, history, decider, local).ok()?;
        let (centre, radius) = match chart {
            RigidChart::Sphere(c) => (c.centre, c.radius),
            RigidChart::Cylinder(c) => (c.centre, c.radius),
        };
        Some((e, norm(centre) + radius))
    };
    out.now.frictional = frictional;
    let evaluated = match rigid.shape {
        RigidSurfaceShape::Plane { point, normal } => {
            let facet = plane_facet(point, normal, plane_half, offset, origin);
            let e = facet_point(law, (x_s, facet, None), history, decider, local).ok();
            local.keep_slave();
            e.map(|e| (e, plane_half))
        }
        RigidSurfaceShape::Sphere { centre, radius } => {
            let chart = SphereChart::for_slave(about(centre), radius, centre, origin);
            on_chart(RigidChart::Sphere(chart), local)
        }
        RigidSurfaceShape::Cylinder { point, axis, radius } => {
            let centre = about(point);
            on_chart(RigidChart::Cylinder(CylinderChart { centre, axis, radius }), local)
        }
    };
    let Some((e, scale)) = evaluated else {
        return out;
    };
    if e.projection.gap > pair.search_radius {
        return out;
    }
    out.now.facet = Some(0);
    out.now.eval = Some(in_model_coordinates(e, origin));
    out.dofs[..3].copy_from_slice(&[3 * node, 3 * node + 1, 3 * node + 2]);
    // the gap is computed from the rigid geometry's coordinates about the origin
    for (p, x) in out.positions.iter_mut().zip(x_s) {
        *p = x.abs().max(scale);
    }
    out
}

/// The evaluation with its contact point in the model's coordinates again (the kernel
/// computed about the slave's origin).
fn in_model_coordinates(mut e: PointEval<f64>, origin: [f64; 3]) -> PointEval<f64> {
    let rho = &mut e.projection.point.rho;
    *rho = std::array::from_fn(|c| rho[c] + origin[c]);
    e
}

/// Whether the point is closed at this evaluation.
pub fn is_closed(now: &SurfaceNow) -> bool {
    now.eval.is_some_and(|e| e.state != ContactState::Open)
}
