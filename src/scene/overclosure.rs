//! Small initial overclosures closed strain-free: slave nodes that start inside their master
//! by round-off, or by the digits a mesh was written to, are moved onto it.
//!
//! Meshes written independently of each other overlap at their interface by a few digits
//! (a block whose bottom is at `y = −1e-5` on a rigid plane at `y = 0`, two bodies meshed to
//! 6 significant digits). Left as they are, the first increment starts with forces from a
//! penetration nobody meant, and against a rigid master the scene was refused as "starting
//! inside". The rule (Abaqus calls it adjusting the initial positions of slave nodes,
//! *CONTACT INTERFERENCE / ADJUST): a slave node of a pair that, at `t = 0`, projects onto
//! its master (`|ξ| ≤ 1`) with a gap `ζ < 0` no deeper than [`ADJUST_SHARE`] of the smaller
//! element at the interface (the smallest element edge at the node, or the master segment's
//! length) is moved to its contact point `ρ(ξ)` — a change of the reference mesh, so no
//! strain and no force. Deeper overlaps are not touched: they are either meant (a press fit,
//! `allow_initial_penetration`) or a mistake (an outline listed the wrong way round, refused
//! by [`super::initial_contact`]). Each pair's adjustment is one note on the model, which
//! `contrail check` prints and a run logs first.

use super::types::SceneFile;
use crate::contact::pairing;
use crate::contact::system::Config;
use crate::model::{Model, Slave};

/// The deepest overlap that is adjusted, as a share of the smaller element at the interface.
pub const ADJUST_SHARE: f64 = 0.01;

/// One node to move: where to, and by how much of its element.
struct Move {
    node: usize,
    to: [f64; 2],
    depth: f64,
    share: f64,
}

/// The slave nodes of pair `ip` that start inside its master within the adjustable depth.
fn small_overlaps(m: &Model, ip: usize, sizes: &[f64], roundoff: f64) -> Vec<Move> {
    let u = vec![0.0; m.dof_count()];
    let cfg = Config {
        model: m,
        u: &u,
        t: 0.0,
    };
    let pair = &m.contacts[ip];
    let mut grid = None;
    let mut moves = Vec::new();
    for &slave in &pair.slaves {
        let Slave::Node(node) = slave else { continue };
        let Some(loc) = pairing::locate(&cfg, pair, slave, None, false, &mut grid, 0.0).located else {
            continue;
        };
        let seg = cfg.segment(pair, loc.segment);
        let (rho, _) = seg.eval(loc.xi);
        let seg_len = {
            let (a, b) = (seg.eval(-1.0).0, seg.eval(1.0).0);
            (a[0] - b[0]).hypot(a[1] - b[1])
        };
        let h = sizes[node].min(seg_len);
        let depth = -loc.gap;
        if depth > roundoff && depth <= ADJUST_SHARE * h && loc.xi.abs() <= 1.0 {
            moves.push(Move {
                node,
                to: rho,
                depth,
                share: depth / h,
            });
        }
    }
    moves
}

/// Move the slave nodes of every pair that allows it onto their master where they start
/// inside it by at most [`ADJUST_SHARE`] of their element (module docs), and note each
/// pair's adjustment on the model.
pub(super) fn adjust_overclosures(m: &mut Model, s: &SceneFile) {
    let roundoff = super::initial_contact::PENETRATION_TOL * m.size();
    let sizes = m.smallest_edge_at_nodes();
    for ip in 0..m.contacts.len() {
        // the pair's own spec, also for the pairs it implies (`NAME/second-pass`)
        let name = &m.contacts[ip].name;
        let spec = (s.contacts.iter()).find(|c| *name == c.name || name.starts_with(&format!("{}/", c.name)));
        if spec.is_some_and(|c| !c.adjust_overclosure || c.allow_initial_penetration) {
            continue;
        }
        let moves = small_overlaps(m, ip, &sizes, roundoff);
        let Some(deepest) = moves.iter().max_by(|a, b| a.depth.total_cmp(&b.depth)) else {
            continue;
        };
        let note = format!(
            "contact `{}`: {} slave nodes started inside the master by up to {:.3e} ({:.2} % of the element at the \
             interface; node {} the deepest): moved onto it, strain-free (adjust_overclosure = false keeps them)",
            m.contacts[ip].name,
            moves.len(),
            deepest.depth,
            100.0 * deepest.share,
            deepest.node
        );
        for mv in &moves {
            m.nodes[mv.node] = mv.to;
        }
        m.notes.push(note);
    }
}
