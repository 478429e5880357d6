//! The load–displacement monitors of a converged increment.
//!
//! - A node set: the mean displacement of its nodes in the monitored direction and the sum of
//!   the forces on them (the reaction where the DOF is prescribed, the applied load elsewhere).
//! - A rigid body: its prescribed travel (the motion law at `t`, i.e. the translation from
//!   its scene position) and the force its drive applies to hold that travel — the
//!   reaction of the prescribed motion, as for a node set's prescribed DOFs, so that a punch
//!   pressed down with `sign = −1` plots in the first quadrant. It is the negative of the sum
//!   of the contact forces the body *receives* in that direction,
//!   taken from the contact point snapshots of the converged state: a slave point of a pair
//!   receives `f`, the force its assembled residual puts on it (`N n + T τ`, normal force
//!   along the master's outward normal and returned tangential traction along the unit
//!   tangent, on a straight master; with the curvature factor `1/(1 − ζ κ)` of `∇ξ` on a
//!   curved one; along the vertex-to-slave line for a point pinned to a concave vertex);
//!   the master of that pair receives `−f` (the point's residual is invariant under a
//!   translation of all its nodes, so its forces sum to zero). The rigid body's force is
//!   the sum of `−f` over the closed points of the pairs whose master it is, and of `f`
//!   over the pairs whose slave is one of its points or vertices. The contact force is what
//!   holds the prescribed motion: its negative is the force the drive applies.

use crate::assembly::Assembler;
use crate::contact::events::PointSnapshot;
use crate::contact::law::ContactState;
use crate::contact3d::system::SurfaceSnapshot;
use crate::model::{Dim, Master, Model, Monitor, MonitorTarget, Slave, SurfaceMaster};
use crate::record::MonitorRecord;

/// The records of all monitors of `model` at the converged state `u`, load level `t`.
pub fn records<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    u: &[f64],
    t: f64,
    (points, surface): (&[PointSnapshot], &[SurfaceSnapshot]),
) -> Vec<MonitorRecord> {
    model
        .monitors
        .iter()
        .map(|m| record(model, m, asm, u, t, (points, surface)))
        .collect()
}

fn record<S: Dim>(
    model: &Model<S>,
    m: &Monitor,
    asm: &Assembler<S>,
    u: &[f64],
    t: f64,
    (points, surface): (&[PointSnapshot], &[SurfaceSnapshot]),
) -> MonitorRecord {
    let (displacement, force) = match &m.target {
        MonitorTarget::Nodes(nodes) => {
            let mut disp = 0.0;
            let mut force = 0.0;
            for &n in nodes {
                let d = S::D * n + m.component;
                disp += u[d];
                force += if asm.dofs.is_prescribed(d) {
                    asm.r_full[d]
                } else {
                    model.loads.iter().filter(|l| l.dof == d).map(|l| l.ramp.at(t)).sum()
                };
            }
            (disp / nodes.len().max(1) as f64, force)
        }
        MonitorTarget::Moment { nodes, point } => moment(model, asm, u, t, nodes, *point, m.component),
        MonitorTarget::Rigid(r) => {
            let travel = model.rigid[*r].offset(t)[m.component];
            // the drive's force: the negative of the contact force received
            (travel, -rigid_contact_force(model.plane(), *r, points)[m.component])
        }
        MonitorTarget::RigidSurface(name) => rigid_surface(model, name, t, surface, m.component),
    };
    MonitorRecord {
        label: m.label.clone(),
        displacement: m.sign * displacement,
        force: m.sign * m.force_scale * force,
    }
}

/// The turn of the node set `nodes` (3D) about the axis along `c` through `p` and the
/// moment of its forces about that axis: `θ = atan2(Σ (a × b)_c, Σ a · b)` over the nodes'
/// arms `a = X − p` (reference) and `b = x − p` (current), across the axis; `M = Σ (b × f)_c`
/// with `f` the node's reaction where prescribed, its applied load elsewhere.
fn moment<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    u: &[f64],
    t: f64,
    nodes: &[usize],
    p: [f64; 3],
    c: usize,
) -> (f64, f64) {
    let (i, j) = ((c + 1) % 3, (c + 2) % 3);
    let (mut sin, mut cos, mut m) = (0.0, 0.0, 0.0);
    for &n in nodes {
        let x = model.nodes[n].as_ref();
        let a = [x[i] - p[i], x[j] - p[j]];
        let b = [a[0] + u[3 * n + i], a[1] + u[3 * n + j]];
        let force = |k: usize| {
            let d = 3 * n + k;
            if asm.dofs.is_prescribed(d) {
                asm.r_full[d]
            } else {
                model.loads.iter().filter(|l| l.dof == d).map(|l| l.ramp.at(t)).sum()
            }
        };
        sin += a[0] * b[1] - a[1] * b[0];
        cos += a[0] * b[0] + a[1] * b[1];
        m += b[0] * force(j) - b[1] * force(i);
    }
    (sin.atan2(cos), m)
}

/// A 3D rigid surface's travel along `c` and its drive's force: the sum of the assembled
/// forces of the closed points of the pairs whose master it is, on their slaves (the surface
/// receives their negative; its drive holds it with the negative of that).
fn rigid_surface<S: Dim>(model: &Model<S>, name: &str, t: f64, surface: &[SurfaceSnapshot], c: usize) -> (f64, f64) {
    let Some(solid) = S::solid(model) else {
        return (0.0, 0.0);
    };
    let is_it = |pair: usize| matches!(solid.surface_contacts.get(pair).map(|p| &p.master), Some(SurfaceMaster::Rigid(r)) if r.name == name);
    let travel = (solid.surface_contacts.iter())
        .find_map(|p| match &p.master {
            SurfaceMaster::Rigid(r) if r.name == name => Some(r.offset(t)[c]),
            _ => None,
        })
        .unwrap_or(0.0);
    let closed = |p: &&SurfaceSnapshot| p.eval.is_some_and(|e| e.state != ContactState::Open);
    let force = surface
        .iter()
        .filter(closed)
        .filter(|p| is_it(p.pair))
        .map(|p| p.force[c])
        .sum();
    (travel, force)
}

/// Sum of the contact forces rigid body `r` receives (x, y).
pub fn rigid_contact_force(model: &Model, r: usize, points: &[PointSnapshot]) -> [f64; 2] {
    let mut total = [0.0; 2];
    for p in points.iter().filter(|p| p.state != ContactState::Open) {
        let Some(pair) = model.contacts.get(p.pair) else {
            continue;
        };
        let as_master = matches!(pair.master, Master::Rigid { body, .. } if body == r);
        let as_slave = matches!(p.slave_id, Slave::RigidPoint(b) | Slave::RigidVertex(b, _) if b == r);
        let sign = match (as_master, as_slave) {
            (true, false) => -1.0,
            (false, true) => 1.0,
            _ => continue, // not this body's, or a rigid body against itself (no net force)
        };
        let f = slave_force(p);
        total[0] += sign * f[0];
        total[1] += sign * f[1];
    }
    total
}

/// The contact force on the slave of a closed point, as assembled at the converged state
/// (`N n + T τ` on a straight master; see [`PointSnapshot::force`]).
pub fn slave_force(p: &PointSnapshot) -> [f64; 2] {
    p.force
}
