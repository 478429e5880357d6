//! What the extrusion and the revolution of a plane scene share (`super::extrude`,
//! `super::revolve`): where a refusal points, the scene copied for 3D, nodal histories
//! scaled, and the contact pairs with their penalties per unit area.

use super::mesh_spec::MeshSpec;
use super::types::{NodeSelection, RampSpec, SceneFile};
use super::{SceneError, SceneSource};
use crate::model::mesh::{axis_coords, AxisGrading};

/// A refusal of `[table] build = true`, located at the table.
pub(super) fn table_err(src: &SceneSource, table: &str, message: String, hint: &str) -> SceneError {
    let location = src.text.find(&format!("[{table}]")).map_or(String::new(), |off| {
        let (l, c) = super::line_col(&src.text, off);
        format!(":{l}:{c}")
    });
    SceneError::Invalid {
        origin: src.origin.clone(),
        location,
        message: format!("[{table}] build = true: {message}"),
        hint: hint.into(),
    }
}

/// The scene copied for its 3D build (`what` it is built as, for the description); body loads
/// and pressures are refused (3D has neither yet).
pub(super) fn start(src: &SceneSource, table: &str, s: &SceneFile, what: &str) -> Result<SceneFile, SceneError> {
    if !s.body_loads.is_empty() || !s.pressures.is_empty() {
        return Err(table_err(
            src,
            table,
            "body loads and pressures have no 3D counterpart yet".into(),
            "give the load as nodal [[load]] totals, or build the scene in 2D",
        ));
    }
    let mut out = s.clone();
    out.extrusion = None;
    out.revolution = None;
    out.description = format!("{} — built in 3D as {what}", s.description);
    Ok(out)
}

/// The contact pairs in 3D: a rigid slave point or a smoothed 2D master refused; penalties
/// per node become per unit area (over [`slave_spacing`]); slave nodes mapped by `nodes`
/// (body, selection) and master faces, one by one, by `faces` (body, face).
#[allow(clippy::type_complexity)]
pub(super) fn contact_pairs(
    src: &SceneSource,
    table: &str,
    s: &SceneFile,
    out: &mut SceneFile,
    nodes: &dyn Fn(&str, &NodeSelection) -> Result<NodeSelection, SceneError>,
    faces: &dyn Fn(&str, &str) -> Result<String, SceneError>,
) -> Result<(), SceneError> {
    for (c, written) in out.contacts.iter_mut().zip(&s.contacts) {
        if c.slave.rigid.is_some() || c.master_smoothing.is_some() {
            return Err(table_err(
                src,
                table,
                format!(
                    "contact `{}`: a rigid slave point or a smoothed 2D master has no 3D counterpart",
                    c.name
                ),
                "build this scene in 2D",
            ));
        }
        let h = slave_spacing(s, written);
        c.eps_n /= h;
        c.eps_t /= h;
        let body = c.slave.body.clone().unwrap_or_default();
        c.slave.nodes = c.slave.nodes.as_ref().map(|n| nodes(&body, n)).transpose()?;
        let master = c.master.body.clone().unwrap_or_default();
        if let Some(f) = &c.master.face {
            let mapped: Result<Vec<String>, SceneError> = f.split('+').map(|one| faces(&master, one)).collect();
            c.master.face = Some(mapped?.join("+"));
        }
    }
    Ok(())
}

/// A history multiplied by `k`.
pub(super) fn scaled(r: &RampSpec, k: f64) -> RampSpec {
    match r {
        RampSpec::Final(v) => RampSpec::Final(v * k),
        RampSpec::Path(p) => RampSpec::Path(p.iter().map(|[t, v]| [*t, v * k]).collect()),
    }
}

/// The smallest element edge along a contact's slave side (1 for a single node: a 3D edge
/// slave's penalty is per unit length, as a 2D node's is per unit thickness).
pub(super) fn slave_spacing(s: &SceneFile, c: &super::types::ContactSpec) -> f64 {
    let (Some(body), Some(nodes)) = (&c.slave.body, &c.slave.nodes) else {
        return 1.0;
    };
    let Some(MeshSpec::Rectangle {
        size,
        elements,
        grading,
        ..
    }) = s.bodies.iter().find(|b| &b.name == body).map(|b| &b.mesh)
    else {
        return 1.0;
    };
    let coords = |k: usize| axis_coords(size[k], elements[k], AxisGrading::End(grading[k]));
    let along = match nodes {
        NodeSelection::Named(n) if n == "top" || n == "bottom" => Some(coords(0)),
        NodeSelection::Named(n) if n == "left" || n == "right" => Some(coords(1)),
        NodeSelection::Where(w) if w.x.is_some() != w.y.is_some() => {
            Some(if w.x.is_some() { coords(1) } else { coords(0) })
        }
        _ => None,
    };
    along
        .map(|c| c.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min))
        .filter(|h| h.is_finite() && *h > 0.0)
        .unwrap_or(1.0)
}
