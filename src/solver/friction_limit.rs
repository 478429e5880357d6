//! Why an increment may have no solution at all: a body that nothing but frictional contact
//! holds, carrying at the last converged increment (nearly) all the friction its points in
//! contact can hold, is at the Coulomb limit. If the load on it grows further (a block pushed up an incline
//! beyond `W (sin α + μ cos α)`, a weight on a slope steeper than `atan μ`), no static
//! equilibrium exists, and Newton cannot converge at any step: the run must stop there, and
//! it should say that this is the likely reason rather than only "no convergence".

use crate::contact::law::ContactState;
use crate::contact::system::ContactSystem;
use crate::model::{Master, Model, Slave};

/// Fraction of the friction a body's contact can hold (`Σ μ N`) that its points must carry
/// (`Σ |T|`) for the diagnosis: a body pushed to its limit has all its points but a few
/// slipping, the last ones close to the cone (a block on an incline: 20 of 21 slipping, the
/// sum at 0.99).
pub const MOBILISED: f64 = 0.95;

/// The diagnosis of a failed increment when some body is held only by frictional contact and
/// carried, at the last converged increment (`contact`: its evaluations at time `t`), at
/// least [`MOBILISED`] of the friction its points in contact can hold: one sentence to append
/// to the failure's reason, or `None`.
///
/// "Held only by contact": no prescribed degree of freedom on the body's nodes. "Its points in
/// contact": closed points whose slave node or master face belongs to the body. A body with no
/// point in contact is not diagnosed (it is free, not at a friction limit), nor is one that a
/// frictionless point holds (normal forces alone may hold it).
pub fn friction_limit(model: &Model, contact: &ContactSystem, t: f64) -> Option<String> {
    for (b, body) in model.bodies.iter().enumerate() {
        let nodes = body.first_node..body.first_node + body.node_count;
        if model.prescribed.iter().any(|p| nodes.contains(&(p.dof / 2))) {
            continue;
        }
        let (mut closed, mut slipping, mut frictionless) = (0usize, 0usize, false);
        let (mut capacity, mut carried) = (0.0, 0.0);
        for (pair, points) in model.contacts.iter().zip(&contact.current) {
            let master_here = matches!(pair.master, Master::Face { body, .. } if body == b);
            for (slave, now) in pair.slaves.iter().zip(points) {
                let slave_here = matches!(slave, Slave::Node(n) if nodes.contains(n));
                let Some(e) = now.eval.filter(|e| e.state != ContactState::Open) else {
                    continue;
                };
                if !(slave_here || master_here) {
                    continue;
                }
                closed += 1;
                frictionless |= pair.law.mu <= 0.0;
                slipping += usize::from(e.state == ContactState::Slip);
                capacity += pair.law.mu * e.normal_force.max(0.0);
                carried += e.t1.abs() / e.proj.a11.sqrt();
            }
        }
        if closed > 0 && !frictionless && capacity > 0.0 && carried >= MOBILISED * capacity {
            return Some(format!(
                "body `{}` is held only by contact and carried {:.3} of the friction its points can \
                 hold (Σ|T| / Σ μN, {slipping} of {closed} points slipping) at the last converged \
                 increment (t = {t:.6}): the load on it has likely reached what Coulomb friction \
                 can hold, beyond which no static equilibrium exists",
                body.name,
                carried / capacity
            ));
        }
    }
    None
}
