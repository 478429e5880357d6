//! Refusing scenes that cannot be right: slave points that start inside a rigid outline.
//!
//! A rigid outline is listed with the rigid body on the left of travel. Listed the other way
//! round, the body it should press on starts *inside* it: every slave point within reach
//! has a negative gap of the order of its distance to the outline, the first residual pushes
//! the whole face out through the tool, and the run reports a force of the wrong sign that
//! shrinks as the tool goes in — a wrong answer with exit code 0. At `t = 0`, before any
//! increment, the slave points of each pair are located on its rigid master as the solver
//! would (tracking, free ends, vertex regions) and a gap below `−PENETRATION_TOL · L` (`L` the
//! model's size) is an error naming the outline, the deepest point and the fix, unless the
//! pair allows it (`allow_initial_penetration = true`, for an interference on purpose).

use super::build::Ctx;
use super::types::SceneFile;
use super::SceneError;
use crate::contact::pairing;
use crate::contact::system::Config;
use crate::model::{Master, Model, Slave};

/// Relative depth (of the model's size) beyond which a slave point counts as starting inside
/// a rigid outline: far above the round-off of coordinates that touch (a block meshed on a
/// rigid plane), far below any overlap a scene could mean.
pub const PENETRATION_TOL: f64 = 1e-6;

/// Slave points of one pair that start inside its rigid master.
#[derive(Debug, Clone, PartialEq)]
pub struct InitialOverlap {
    pub pair: usize,
    /// How many of the pair's slave points start inside, and the deepest one with its gap.
    pub count: usize,
    pub deepest: Slave,
    pub gap: f64,
    pub position: [f64; 2],
}

/// The pairs (of those with a rigid master and `allowed[pair] == false`) whose slave points
/// start inside their master.
pub fn initial_overlaps(m: &Model, allowed: &[bool]) -> Vec<InitialOverlap> {
    let u = vec![0.0; m.dof_count()];
    let cfg = Config {
        model: m,
        u: &u,
        t: 0.0,
    };
    let tol = PENETRATION_TOL * m.size();
    let mut out = Vec::new();
    for (ip, pair) in m.contacts.iter().enumerate() {
        if allowed.get(ip).copied().unwrap_or(false) || !matches!(pair.master, Master::Rigid { .. }) {
            continue;
        }
        let mut grid = None;
        let mut overlap: Option<InitialOverlap> = None;
        for &slave in &pair.slaves {
            let located = pairing::locate(&cfg, pair, slave, None, false, &mut grid, 0.0).located;
            let gap = match located {
                Some(l) => l.gap,
                None => solid_side_gap(&cfg, pair, slave).unwrap_or(0.0),
            };
            if gap >= -tol {
                continue;
            }
            let o = overlap.get_or_insert(InitialOverlap {
                pair: ip,
                count: 0,
                deepest: slave,
                gap,
                position: cfg.slave_pos(slave),
            });
            o.count += 1;
            if gap < o.gap {
                (o.deepest, o.gap, o.position) = (slave, gap, cfg.slave_pos(slave));
            }
        }
        out.extend(overlap);
    }
    out
}

/// The signed gap of a slave point out of the pair's reach to the nearest point of the
/// rigid outline, when that point lies inside a piece (not at a vertex or an end, where the
/// side is not defined): negative on the solid side. An outline listed the wrong way round
/// while the body is still far from it puts the body on its solid side as surely as one in
/// reach does; unrefused, the tool then sweeps through the body with no force at all.
fn solid_side_gap(cfg: &Config, pair: &crate::model::ContactPair, slave: Slave) -> Option<f64> {
    let rs = cfg.slave_pos(slave);
    let dist = |p: [f64; 2]| (p[0] - rs[0]).hypot(p[1] - rs[1]);
    let (mut best, mut nearest_end) = (None::<f64>, f64::INFINITY);
    for seg in 0..pair.master.segment_count() {
        let g = cfg.segment(pair, seg);
        nearest_end = nearest_end.min(dist(g.eval(-1.0).0)).min(dist(g.eval(1.0).0));
        let p = g.project(rs);
        if p.xi.abs() <= 1.0 && best.is_none_or(|b| p.gap.abs() < b.abs()) {
            best = Some(p.gap);
        }
    }
    best.filter(|b| b.abs() < nearest_end)
}

/// A scene whose slave points start inside a rigid outline is refused (see
/// [`super::initial_contact`]).
pub(super) fn refuse_initial_overlaps(cx: &Ctx, m: &Model, s: &SceneFile) -> Result<(), SceneError> {
    let allowed: Vec<bool> = s.contacts.iter().map(|c| c.allow_initial_penetration).collect();
    let Some(o) = initial_overlaps(m, &allowed).into_iter().next() else {
        return Ok(());
    };
    let pair = &m.contacts[o.pair];
    let Master::Rigid { body, .. } = pair.master else {
        return Ok(());
    };
    let rigid = &m.rigid[body].name;
    Err(cx.err(
        &pair.name,
        format!(
            "contact `{}`: {} of its {} slave points start inside rigid body `{rigid}` — {} by {:.4e} at [{:.6}, {:.6}]",
            pair.name,
            o.count,
            pair.slaves.len(),
            m.slave_label(o.deepest),
            -o.gap,
            o.position[0],
            o.position[1]
        ),
        &format!(
            "a rigid outline is listed with the rigid body on the LEFT of the direction of travel; `contrail check` shows the side of each. If `{rigid}` is listed the other way round, list its points (and pieces) in the reverse order; if the bodies really overlap at the start, move them apart, or set allow_initial_penetration = true on the pair (overlaps up to 1 % of the element at the interface are moved onto the master unless adjust_overclosure = false)"
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_scenes_start_without_overlaps() {
        // the 2D scenes (`initial_overlaps` reads 2D pairs)
        for b in crate::scene::builtin::BUILTINS {
            if let crate::scene::AnyProblem::Plane(p) = crate::load_any_scene(b.name, &[]).unwrap().1 {
                assert!(initial_overlaps(&p.model, &[]).is_empty(), "{}", b.name);
            }
        }
    }
}
