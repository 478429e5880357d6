//! The JSON of the web page's model view, made from a [`Recording`]: the reference mesh and
//! the index of increments (`GET /api/runs/{id}/model`), and one increment's node positions
//! and contact points (`GET /api/runs/{id}/model/{increment}`). Coordinates are flat arrays
//! of `dim` numbers per point (single precision: they are for drawing); a 3D run's answer
//! (`dim = 3`) is made by [`super::model_json3d`].

use super::model_json3d as solid;
use contrail::analysis::recording::Recording;
use contrail::record::mcap::sink::node_of_label;
use contrail::record::messages::PositionsMessage;
use contrail::record::ContactPointRecord;
use serde_json::{json, Value};

/// Space dimension of a plane model.
const DIM: usize = 2;

/// Points as a flat `[x0, y0, x1, y1, …]` list in single precision (NaN: null).
fn flat(points: impl IntoIterator<Item = [f64; 2]>) -> Vec<f32> {
    points.into_iter().flat_map(|p| [p[0] as f32, p[1] as f32]).collect()
}

/// The increment asked for is not one the recording has.
#[derive(Debug, PartialEq)]
pub enum FrameError {
    /// The recording has no increment of that number (the numbers it has, first and last).
    NoSuchIncrement { asked: usize, last: Option<usize> },
}

impl std::fmt::Display for FrameError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FrameError::NoSuchIncrement { asked, last: Some(last) } => write!(
                f,
                "increment {asked} is not recorded: the recording has increments 1 to {last} (0 is the reference configuration)"
            ),
            FrameError::NoSuchIncrement { asked, last: None } => write!(
                f,
                "increment {asked} is not recorded: the recording has no increment yet (0 is the reference configuration)"
            ),
        }
    }
}

/// The index of increments: number, load level, Newton iterations, cut-backs, contact points
/// (2D and 3D) and the first monitor's displacement and force of each (parallel arrays).
fn frames(rec: &Recording) -> Value {
    let incs = &rec.increments;
    let monitor = |f: fn(&contrail::record::MonitorRecord) -> f64| -> Vec<Option<f64>> {
        incs.iter().map(|i| i.monitor.as_ref().map(f)).collect()
    };
    json!({
        "increment": incs.iter().map(|i| i.increment).collect::<Vec<_>>(),
        "t": incs.iter().map(|i| i.t).collect::<Vec<_>>(),
        "iterations": incs.iter().map(|i| i.iterations).collect::<Vec<_>>(),
        "cutbacks": incs.iter().map(|i| i.cutbacks).collect::<Vec<_>>(),
        "converged": incs.iter().map(|i| i.converged).collect::<Vec<_>>(),
        "contact": incs.iter().map(|i| rec.contact_at(i.increment).len() + rec.surface_at(i.increment).len()).collect::<Vec<_>>(),
        "displacement": monitor(|m| m.displacement),
        "force": monitor(|m| m.force),
    })
}

/// Grows a box `[xmin, ymin, xmax, ymax]` to hold a point (non-finite points are skipped).
fn grow(b: &mut [f64; 4], p: [f64; 2]) {
    if p[0].is_finite() && p[1].is_finite() {
        *b = [b[0].min(p[0]), b[1].min(p[1]), b[2].max(p[0]), b[3].max(p[1])];
    }
}

/// `[xmin, ymin, xmax, ymax]` that the page fits to its canvas: the nodes at every recorded
/// increment, and the vertices of the rigid bodies (at every recorded offset) that lie near
/// them: within a quarter of the nodes' diagonal (a rigid wall or plane may reach far
/// beyond the bodies; it is drawn cut off at the frame).
fn bounds(rec: &Recording) -> [f64; 4] {
    let mut b = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
    rec.model.nodes.iter().for_each(|&p| grow(&mut b, p));
    rec.positions
        .iter()
        .flat_map(|p| &p.nodes)
        .for_each(|&p| grow(&mut b, p));
    let near = if b[0] <= b[2] {
        let reach = 0.25 * (b[2] - b[0]).hypot(b[3] - b[1]);
        [b[0] - reach, b[1] - reach, b[2] + reach, b[3] + reach]
    } else {
        [f64::NEG_INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::INFINITY]
    };
    let no_offsets = vec![[0.0; 2]; rec.model.rigid.len()];
    let offsets = std::iter::once(&no_offsets).chain(rec.positions.iter().map(|p| &p.rigid_offsets));
    for off in offsets {
        for (r, o) in rec.model.rigid.iter().zip(off) {
            for p in r.pieces.iter().flatten() {
                let q = [p[0] + o[0], p[1] + o[1]];
                if q[0] >= near[0] && q[0] <= near[2] && q[1] >= near[1] && q[1] <= near[3] {
                    grow(&mut b, q);
                }
            }
        }
    }
    if b[0] > b[2] {
        return [0.0, 0.0, 1.0, 1.0];
    }
    b
}

/// The force a contact point's slave receives: the recorded one, or (older recordings)
/// `normal_force · normal + traction · tangent`.
fn force_of(p: &ContactPointRecord) -> [f64; 2] {
    if p.force.iter().all(|f| f.is_finite()) {
        return p.force;
    }
    [0, 1].map(|k| p.normal_force * p.normal[k] + p.traction * p.tangent[k])
}

/// Largest contact force (magnitude) of the run, and largest normal force and tangential
/// traction: the page scales its arrows by them, the same at every increment.
fn largest_forces(rec: &Recording) -> Value {
    let (mut total, mut normal, mut tangential) = (0.0f64, 0.0f64, 0.0f64);
    for p in rec.contact.values().flatten() {
        let f = force_of(p);
        total = total.max(f[0].hypot(f[1]).abs());
        normal = normal.max(p.normal_force.abs());
        tangential = tangential.max(p.traction.abs());
    }
    // NaN never wins a max: these are finite or zero
    json!({ "force": total, "normal_force": normal, "traction": tangential })
}

/// `GET /api/runs/{id}/model`: the reference mesh (unless `mesh` is false: the index only,
/// for a page that follows a running run), the rigid surfaces, the contact pairs, the index
/// of increments, the increments that have node positions, the run's bounds and largest
/// forces.
pub fn model(rec: &Recording, mesh: bool) -> Value {
    let m = &rec.model;
    let plane = !solid::is_3d(rec);
    let mut v = json!({
        "dim": DIM,
        "name": m.name,
        "end": m.end,
        "monitor": m.monitor_labels().first(),
        "node_count": m.nodes.len(),
        "element_count": m.elements.len(),
        "nodes_per_element": 4,
        "frames": frames(rec),
        "positions_at": rec.positions.iter().map(|p| p.increment).collect::<Vec<_>>(),
        "positions_every": rec.metadata.get("positions_every").and_then(|s| s.parse::<usize>().ok()),
        "bounds": if plane { json!(bounds(rec)) } else { Value::Null },
        "largest": if plane { largest_forces(rec) } else { Value::Null },
        "outcome": rec.outcome.as_ref().and_then(|o| serde_json::to_value(o).ok()),
    });
    if mesh {
        v["bodies"] = json!(m
            .bodies
            .iter()
            .map(|b| json!({ "name": b.name, "element": b.element, "first_node": b.first_node, "node_count": b.node_count }))
            .collect::<Vec<_>>());
    }
    if !plane {
        return solid::model(rec, mesh, v);
    }
    if mesh {
        v["nodes"] = json!(flat(m.nodes.iter().copied()));
        v["elements"] = json!(m.elements.iter().flatten().collect::<Vec<_>>());
        v["element_body"] = json!(m.element_body);
        v["rigid"] = json!(m
            .rigid
            .iter()
            .map(|r| json!({ "name": r.name, "kind": r.kind, "pieces": r.pieces.iter().map(|p| flat(p.iter().copied())).collect::<Vec<_>>() }))
            .collect::<Vec<_>>());
        v["pairs"] = json!(m
            .contacts
            .iter()
            .map(|c| json!({ "name": c.name, "master": c.master, "mu": c.mu, "slaves": c.slaves.len() }))
            .collect::<Vec<_>>());
    }
    v
}

/// The positions shown at `increment`: its own, else the nearest earlier recorded ones, else
/// the reference configuration (increment 0).
fn positions_at(rec: &Recording, increment: usize) -> (usize, Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let before = rec
        .positions
        .iter()
        .filter(|p| p.increment <= increment)
        .max_by_key(|p| p.increment);
    match before {
        Some(PositionsMessage {
            increment,
            nodes,
            rigid_offsets,
            ..
        }) => (*increment, nodes.clone(), rigid_offsets.clone()),
        None => (0, rec.model.nodes.clone(), vec![[0.0; 2]; rec.model.rigid.len()]),
    }
}

/// The contact points of an increment as parallel arrays (vectors flat, `dim` per point).
fn contact_arrays(rec: &Recording, points: &[ContactPointRecord]) -> Value {
    // `rigid NAME` or `rigid NAME vertex K`
    let rigid_of = |label: &str| {
        let rest = label.strip_prefix("rigid ")?;
        rec.model.rigid.iter().position(|r| {
            rest.strip_prefix(r.name.as_str())
                .is_some_and(|tail| tail.is_empty() || tail.starts_with(" vertex "))
        })
    };
    json!({
        "count": points.len(),
        "pair": points.iter().map(|p| p.pair).collect::<Vec<_>>(),
        "slave": points.iter().map(|p| p.slave_label.as_ref()).collect::<Vec<_>>(),
        "node": points.iter().map(|p| node_of_label(&p.slave_label)).collect::<Vec<_>>(),
        "rigid": points.iter().map(|p| rigid_of(&p.slave_label)).collect::<Vec<_>>(),
        "state": points.iter().map(|p| p.state).collect::<Vec<_>>(),
        "segment": points.iter().map(|p| p.segment).collect::<Vec<_>>(),
        "position": flat(points.iter().map(|p| p.position)),
        "normal": flat(points.iter().map(|p| p.normal)),
        "tangent": flat(points.iter().map(|p| p.tangent)),
        "force": flat(points.iter().map(force_of)),
        "normal_force": points.iter().map(|p| p.normal_force as f32).collect::<Vec<_>>(),
        "traction": points.iter().map(|p| p.traction as f32).collect::<Vec<_>>(),
        "gap": points.iter().map(|p| p.gap as f32).collect::<Vec<_>>(),
    })
}

/// `GET /api/runs/{id}/model/{increment}`: the increment's load level, iterations and
/// monitors, the node positions shown (`positions_increment` says whose: the increment's
/// own when `positions_exact`), the rigid offsets, and its contact points.
pub fn frame(rec: &Recording, increment: usize) -> Result<Value, FrameError> {
    let record = rec.increments.iter().find(|i| i.increment == increment);
    if increment != 0 && record.is_none() {
        return Err(FrameError::NoSuchIncrement {
            asked: increment,
            last: rec.increments.iter().map(|i| i.increment).max(),
        });
    }
    let (dim, shown, nodes, offsets, contact) = if solid::is_3d(rec) {
        let (shown, nodes) = solid::positions_at(rec, increment);
        let points = if increment == 0 {
            &[][..]
        } else {
            rec.surface_at(increment)
        };
        let offsets = solid::offsets_at(rec, increment);
        (3, shown, nodes, offsets, solid::contact_arrays(points))
    } else {
        let (shown, nodes, offsets) = positions_at(rec, increment);
        let points = if increment == 0 {
            &[][..]
        } else {
            rec.contact_at(increment)
        };
        (DIM, shown, flat(nodes), flat(offsets), contact_arrays(rec, points))
    };
    Ok(json!({
        "dim": dim,
        "increment": increment,
        "t": record.map_or(0.0, |r| r.t),
        "dt": record.map(|r| r.dt),
        "iterations": record.map(|r| r.iterations),
        "cutbacks": record.map(|r| r.cutbacks),
        "converged": record.map(|r| r.converged),
        "monitors": record.map(|r| json!(r.monitors)),
        "positions_increment": shown,
        "positions_exact": shown == increment,
        "nodes": nodes,
        "rigid_offsets": offsets,
        "contact": contact,
    }))
}

#[cfg(test)]
#[path = "model_json_tests.rs"]
mod tests;
