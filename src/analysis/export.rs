//! `contrail export FILE.mcap --vtu DIR`: the VTU series of a recording (the format of
//! [`crate::record::vtu::file`]), for every increment that has `/positions` (all of them, or every
//! N-th and the last with `run --positions-every N`).
//!
//! The recording holds the reference mesh, the current positions and the contact points, but
//! not the materials: stress and strain need the model, which the caller rebuilds from the
//! scene attached to the recording; without it (or if it does not match the recorded mesh)
//! the series has the displacement and the contact points only.

use super::recording::Recording;
use crate::model::Model;
use crate::record::vtu::file::{contact_piece, mesh_piece};
use crate::record::vtu::sink::{model_piece, VtuSeries};
use std::io;
use std::path::Path;

/// What an export wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportSummary {
    /// Increments written (one `.vtu` of the mesh each, and one of the contact points).
    pub steps: usize,
    /// Whether the mesh files have stress and strain.
    pub fields: bool,
}

/// Whether `model` is the model the recording was made with (same nodes and elements).
pub fn matches(model: &Model, r: &Recording) -> bool {
    model.nodes == r.model.nodes
        && model.elements.len() == r.model.elements.len()
        && model.elements.iter().zip(&r.model.elements).all(|(e, q)| e.nodes == *q)
}

/// Write the series of `r` as `pvd` (and the directory beside it); `model` (if it
/// [`matches`]) gives the element fields.
pub fn export_vtu(r: &Recording, model: Option<&Model>, pvd: &Path) -> io::Result<ExportSummary> {
    let model = model.filter(|m| matches(m, r));
    let mut series = VtuSeries::create(pvd)?;
    let no_contact = Vec::new();
    for p in &r.positions {
        if p.nodes.len() != r.model.nodes.len() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "/positions of increment {} has {} nodes, the model {}",
                    p.increment,
                    p.nodes.len(),
                    r.model.nodes.len()
                ),
            ));
        }
        let u: Vec<f64> = p
            .nodes
            .iter()
            .zip(&r.model.nodes)
            .flat_map(|(x, x0)| [x[0] - x0[0], x[1] - x0[1]])
            .collect();
        let mesh = match model {
            Some(m) => model_piece(m, &u),
            None => mesh_piece(&r.model.nodes, &r.model.elements, &r.model.element_body, &u, None),
        };
        let contact =
            (!r.model.contacts.is_empty()).then(|| contact_piece(r.contact.get(&p.increment).unwrap_or(&no_contact)));
        series.step(p.increment, p.t, &mesh, contact.as_ref())?;
    }
    series.finish()?;
    Ok(ExportSummary {
        steps: series.steps(),
        fields: model.is_some(),
    })
}
