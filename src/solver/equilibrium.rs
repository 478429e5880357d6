//! The global equilibrium of each deformable body at a converged increment, checked from
//! forces gathered independently of the residual test.
//!
//! For body `b` the resultant of everything acting on it,
//!
//! `F_b = Σ_{loads on b} f  +  Σ_{prescribed DOFs of b} r  +  Σ_{points} ±f_c`,
//!
//! must vanish: `f` the applied nodal loads at `t` (body forces included: the scene lumps
//! them into nodal loads), `r` the reactions (the residual at the prescribed DOFs), and
//! `f_c = N n + T τ` the contact force of each closed point as its snapshot records it
//! ([`super::monitor::slave_force`]; in 3D the assembled force of each node-to-surface
//! point, [`SurfaceSnapshot::force`]): `+f_c` on the body of a slave node, `−f_c` on the
//! body of a deformable master face (the point's residual is invariant under a translation
//! of its nodes, so its forces on slave and master sum to zero). Internal forces sum to
//! zero over a body (translation invariance of the strain energy), so `F_b` is minus the
//! sum of the free residual over the body *if* the recorded contact forces are the ones
//! assembled: the check fails when a record or the assembly lost or misplaced a force, or
//! when the free residual, small in norm, is not small in its sum.
//!
//! An axisymmetric body's resultant is its axial component alone (`x = r` set to zero): a
//! radial translation is no rigid motion of a body of revolution (it strains the hoops), so
//! its internal forces do not sum to zero along `r` — the radial forces of the rings are
//! balanced by the hoop stresses, not by each other.
//!
//! The imbalance is `max_b |F_b| / F`, `F` the force scale of the convergence test
//! ([`super::newton::force_scale`]) but at least [`NOISE_TO_SCALE`] times the residual's
//! round-off floor (`Assembler::roundoff`: in a model still without load every force is
//! noise, and so is its sum); it is recorded per increment (`/increment` `equilibrium`)
//! and its worst in the summary.

use crate::assembly::Assembler;
use crate::contact::events::PointSnapshot;
use crate::contact::law::ContactState;
use crate::contact3d::system::SurfaceSnapshot;
use crate::model::{Dim, Master, Model, Slave, SurfaceMaster};

/// An imbalance above this (relative to `F_ref`) stops the run: a force was lost between the
/// assembly and the records. Converged increments of the built-in scenes measure 3.2e-15 to
/// 2.0e-9 (2026-11-27, `contrail run NAME`, the summary's `equilibrium` line).
pub const EQUILIBRIUM_TOLERANCE: f64 = 1e-6;

/// The force scale of the imbalance is at least this many times the residual's round-off
/// floor: a body's sum of noise-level residuals (up to `10³` of the floor for `10⁶` DOFs)
/// stays below [`EQUILIBRIUM_TOLERANCE`].
pub const NOISE_TO_SCALE: f64 = 1e9;

/// The worst body of a converged state: its index and its relative imbalance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Imbalance {
    pub body: usize,
    /// `|F_b| / F_ref`.
    pub relative: f64,
    /// `F_b` itself (x, y, z; z zero in 2D).
    pub resultant: [f64; 3],
}

/// The resultant force on every body of `model` (x, y, z; z zero in 2D), gathered as in the
/// module doc.
pub fn body_resultants<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    t: f64,
    points: &[PointSnapshot],
    surface: &[SurfaceSnapshot],
) -> Vec<[f64; 3]> {
    let mut totals = Totals::new(model);
    for l in &model.loads {
        totals.add(l.dof / S::D, l.dof % S::D, l.ramp.at(t));
    }
    for &d in &asm.dofs.prescribed {
        totals.add(d / S::D, d % S::D, asm.r_full[d]);
    }
    add_segment_contacts(&mut totals, model, points);
    add_surface_contacts(&mut totals, model, surface);
    let mut total = totals.total;
    if let Some(plane) = (S::D == 2).then(|| model.plane()) {
        for (b, body) in plane.bodies.iter().enumerate() {
            if body.kinematics == crate::element::quad::Kinematics::Axisymmetric {
                total[b][0] = 0.0;
            }
        }
    }
    total
}

/// Forces summed per body, by the body that owns each node.
struct Totals {
    body_of_node: Vec<usize>,
    total: Vec<[f64; 3]>,
}

impl Totals {
    fn new<S: Dim>(model: &Model<S>) -> Self {
        let mut body_of_node = vec![usize::MAX; model.nodes.len()];
        for (b, body) in model.bodies.iter().enumerate() {
            body_of_node[body.first_node..body.first_node + body.node_count].fill(b);
        }
        Totals {
            body_of_node,
            total: vec![[0.0; 3]; model.bodies.len()],
        }
    }

    /// Component `comp` of a force `f` on `node` (nodes of no body are left out).
    fn add(&mut self, node: usize, comp: usize, f: f64) {
        if let Some(t) = self.body_of_node.get(node).and_then(|&b| self.total.get_mut(b)) {
            t[comp] += f;
        }
    }
}

/// The forces of the closed 2D points: on the slave node, and its reaction on the first
/// node of a deformable master segment.
fn add_segment_contacts<S: Dim>(totals: &mut Totals, model: &Model<S>, points: &[PointSnapshot]) {
    for p in points.iter().filter(|p| p.state != ContactState::Open) {
        let Some(pair) = model.contacts.get(p.pair) else {
            continue;
        };
        let f = super::monitor::slave_force(p);
        if let Slave::Node(n) = p.slave_id {
            totals.add(n, 0, f[0]);
            totals.add(n, 1, f[1]);
        }
        if let (Master::Face { segments, .. }, Some(s)) = (&pair.master, p.segment) {
            if let Some(&[a, _]) = segments.get(s) {
                totals.add(a, 0, -f[0]);
                totals.add(a, 1, -f[1]);
            }
        }
    }
}

/// The forces of the closed 3D points: on the slave node, and its reaction on the first
/// node of a deformable master facet.
fn add_surface_contacts<S: Dim>(totals: &mut Totals, model: &Model<S>, surface: &[SurfaceSnapshot]) {
    let closed = |p: &&SurfaceSnapshot| p.eval.is_some_and(|e| e.state != ContactState::Open);
    for p in surface.iter().filter(closed) {
        for c in 0..3 {
            totals.add(p.node, c, p.force[c]);
        }
        let master = S::solid(model)
            .and_then(|m| m.surface_contacts.get(p.pair))
            .map(|pair| &pair.master);
        if let (Some(SurfaceMaster::Facets { facets, .. }), Some(f)) = (master, p.facet) {
            if let Some(&[a, ..]) = facets.get(f) {
                for c in 0..3 {
                    totals.add(a, c, -p.force[c]);
                }
            }
        }
    }
}

/// The body with the largest resultant relative to `fref` or, where larger, the noise
/// scale (module docs); `None` for a model without bodies.
pub fn worst_imbalance<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    t: f64,
    points: &[PointSnapshot],
    surface: &[SurfaceSnapshot],
    fref: f64,
) -> Option<Imbalance> {
    let scale = fref.max(NOISE_TO_SCALE * asm.roundoff()).max(f64::MIN_POSITIVE);
    body_resultants(model, asm, t, points, surface)
        .into_iter()
        .enumerate()
        .map(|(body, r)| Imbalance {
            body,
            relative: r[0].hypot(r[1]).hypot(r[2]) / scale,
            resultant: r,
        })
        .max_by(|a, b| a.relative.total_cmp(&b.relative))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::events::PointSnapshot;

    fn closed_point(pair: usize, slave: Slave, segment: usize, force: [f64; 2]) -> PointSnapshot {
        PointSnapshot {
            pair,
            slave: 0,
            slave_id: slave,
            segment: Some(segment),
            previous_segment: Some(segment),
            xi: 0.0,
            xi_anchor: f64::NAN,
            gap: 0.0,
            normal_force: 1.0,
            trial_traction: 0.0,
            traction: 0.0,
            state: ContactState::Slip,
            crossing: false,
            position: [0.0; 2],
            contact_point: [0.0; 2],
            normal: [0.0, 1.0],
            tangent: [1.0, 0.0],
            force,
            multiplier: [f64::NAN; 2],
        }
    }

    /// The applied loads of a body count, and a contact force on one of its nodes balances
    /// them: the capstan's belt, tensioned at both ends, out of equilibrium by the sum of its
    /// loads until a point on it carries their negative.
    #[test]
    fn loads_and_contact_forces_of_a_body_are_summed() {
        let (_, p) = crate::load_scene("capstan", &[]).unwrap();
        let model = &p.model;
        let asm = Assembler::new(model);
        let t = 0.5;
        let loads = model.loads.iter().fold([0.0; 2], |mut s, l| {
            s[l.dof % 2] += l.ramp.at(t);
            s
        });
        assert!(loads[0].hypot(loads[1]) > 0.0);
        let lone = worst_imbalance(model, &asm, t, &[], &[], 1.0).unwrap();
        assert!((lone.resultant[0] - loads[0]).abs() < 1e-12 && (lone.resultant[1] - loads[1]).abs() < 1e-12);
        let pair = &model.contacts[0];
        let balanced = [closed_point(0, pair.slaves[0], 0, [-loads[0], -loads[1]])];
        let held = worst_imbalance(model, &asm, t, &balanced, &[], 1.0).unwrap();
        assert!(held.relative < 1e-12, "{held:?}");
    }

    /// A point between two deformable bodies puts `+f` on the slave's body and `−f` on the
    /// master's: each alone is out of balance by `|f|`, relative to `F_ref` or the noise scale.
    #[test]
    fn a_point_between_two_bodies_pushes_both_ways() {
        let (_, p) = crate::load_scene("contact-patch", &[]).unwrap();
        let model = &p.model;
        let asm = Assembler::new(model);
        let pair = &model.contacts[0];
        let f = [0.3, -4.0];
        let points = [closed_point(0, pair.slaves[0], 0, f)];
        let r = body_resultants(model, &asm, 0.0, &points, &[]);
        let Master::Face { body: master, .. } = pair.master else {
            panic!("the patch test's pair has a deformable master")
        };
        let Slave::Node(n) = pair.slaves[0] else {
            panic!("a node slave")
        };
        let slave = (model.bodies.iter()).position(|b| (b.first_node..b.first_node + b.node_count).contains(&n));
        assert_eq!(r[slave.unwrap()], [f[0], f[1], 0.0]);
        assert_eq!(r[master], [-f[0], -f[1], 0.0]);
        let worst = worst_imbalance(model, &asm, 0.0, &points, &[], 2.0).unwrap();
        let scale = 2.0f64.max(NOISE_TO_SCALE * asm.roundoff());
        assert!((worst.relative - f[0].hypot(f[1]) / scale).abs() < 1e-15);
    }
}
