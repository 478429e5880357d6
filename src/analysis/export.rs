//! `contrail export FILE.mcap --vtu DIR`: the VTU series of a recording (the format of
//! [`crate::record::vtu::file`]), for every increment that has `/positions` (all of them, or every
//! N-th and the last with `run --positions-every N`).
//!
//! The recording holds the reference mesh, the current positions and the contact points, but
//! not the materials: stress and strain need the model, which the caller rebuilds from the
//! scene attached to the recording; without it (or if it does not match the recorded mesh)
//! the series has the displacement and the contact points only. A recording of the boundary
//! nodes only (`--positions-of surface`) is refused: the cells need every node.

use super::recording::Recording;
use crate::model::{Model, ModelRef, Solid};
use crate::record::vtu::file::{contact_piece, mesh_piece, solid_piece, surface_contact_piece};
use crate::record::vtu::sink::{model_piece, solid_model_piece, VtuSeries};
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

/// Whether `model` is the 3D model the recording was made with (same nodes and hexahedra).
pub fn matches_solid(model: &Model<Solid>, r: &Recording) -> bool {
    model.nodes == r.model.nodes_3d
        && model.elements.len() == r.model.hexahedra.len()
        && model
            .elements
            .iter()
            .zip(&r.model.hexahedra)
            .all(|(e, q)| e.nodes == *q)
}

/// Write the series of `r` as `pvd` (and the directory beside it); `model` (if it
/// [`matches`] or [`matches_solid`]) gives the element fields.
pub fn export_vtu(r: &Recording, model: Option<ModelRef<'_>>, pvd: &Path) -> io::Result<ExportSummary> {
    if !r.model.positions_nodes.is_empty() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "the recording holds the positions of the {} boundary nodes only (`run --positions-of surface`): \
                 a VTU series needs every node; record with `--positions-of all`, or view it with `contrail replay`",
                r.model.positions_nodes.len()
            ),
        ));
    }
    let series = VtuSeries::create(pvd)?;
    if r.model.dim() == 3 {
        let solid = match model {
            Some(ModelRef::Solid(m)) if matches_solid(m, r) => Some(m),
            _ => None,
        };
        return export_solid(r, solid, series);
    }
    let model = match model {
        Some(ModelRef::Plane(m)) if matches(m, r) => Some(m),
        _ => None,
    };
    let mut series = series;
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

/// The series of a 3D recording: the hexahedra with their displacement (and element fields
/// where the model is given) and the 3D contact points.
fn export_solid(r: &Recording, model: Option<&Model<Solid>>, mut series: VtuSeries) -> io::Result<ExportSummary> {
    let m = &r.model;
    for p in &r.positions {
        if p.nodes_3d.len() != m.nodes_3d.len() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "/positions of increment {} has {} nodes, the model {}",
                    p.increment,
                    p.nodes_3d.len(),
                    m.nodes_3d.len()
                ),
            ));
        }
        let u: Vec<f64> = (p.nodes_3d.iter().zip(&m.nodes_3d))
            .flat_map(|(x, x0)| [x[0] - x0[0], x[1] - x0[1], x[2] - x0[2]])
            .collect();
        let mesh = match model {
            Some(model) => solid_model_piece(model, &u),
            None => solid_piece(&m.nodes_3d, &m.hexahedra, &m.element_body, &u, None),
        };
        let contact = (!m.surface_contacts.is_empty()).then(|| surface_contact_piece(r.surface_at(p.increment)));
        series.step(p.increment, p.t, &mesh, contact.as_ref())?;
    }
    series.finish()?;
    Ok(ExportSummary {
        steps: series.steps(),
        fields: model.is_some(),
    })
}
