//! ParaView output: a `.pvd` collection and, for every N-th converged increment (and the
//! last), a `.vtu` of the mesh with its fields and one of the contact points (format in
//! [`crate::record::vtu::file`]). `RUN.pvd` refers to `RUN/RUN_000012.vtu` and `RUN/RUN_contact_000012.vtu`
//! (increment 12). The `.pvd` is written when the run ends — also after a failure or an
//! interruption — under a temporary name and renamed into place.

use crate::element::fields::{centre_fields_with, hex8_centre_fields, CentreFields};
use crate::model::{AnyModel, Model, ModelRef, Solid};
use crate::record::atomic_file::AtomicFile;
use crate::record::surface_contact::SurfacePointRecord;
use crate::record::vtu::file::{
    contact_piece, mesh_piece, solid_piece, surface_contact_piece, write_pvd, write_vtu, Piece, PvdEntry,
};
use crate::record::{ContactPointRecord, IncrementRecord, Observer, ObserverError, Outcome, RunInfo, StepView};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Centre fields of every element of a model for the displacement `u` (`None` where the
/// element cannot be evaluated, e.g. inverted).
pub fn model_fields(model: &Model, u: &[f64]) -> Vec<Option<CentreFields>> {
    model
        .elements
        .iter()
        .map(|e| {
            let body = &model.bodies[e.body];
            let x = e.nodes.map(|n| model.nodes[n]);
            let ue = e.nodes.map(|n| [u[2 * n], u[2 * n + 1]]);
            centre_fields_with(body.kind, &body.material, body.kinematics, &x, &ue).ok()
        })
        .collect()
}

/// The mesh dataset of a model at displacement `u`, with its element fields.
pub fn model_piece(model: &Model, u: &[f64]) -> Piece {
    let quads: Vec<[usize; 4]> = model.elements.iter().map(|e| e.nodes).collect();
    let body: Vec<usize> = model.elements.iter().map(|e| e.body).collect();
    let fields = model_fields(model, u);
    mesh_piece(&model.nodes, &quads, &body, u, Some(&fields))
}

/// Centre fields of every hexahedron of a 3D model for the displacement `u`
/// ([`hex8_centre_fields`]; `None` where the element cannot be evaluated).
pub fn solid_model_fields(model: &Model<Solid>, u: &[f64]) -> Vec<Option<CentreFields>> {
    model
        .elements
        .iter()
        .map(|e| {
            let body = &model.bodies[e.body];
            let x = e.nodes.map(|n| model.nodes[n]);
            let ue = e.nodes.map(|n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]]);
            hex8_centre_fields(body.kind.kind, &body.material, &x, &ue).ok()
        })
        .collect()
}

/// The mesh dataset of a 3D model at displacement `u` (hexahedra), with its element fields.
pub fn solid_model_piece(model: &Model<Solid>, u: &[f64]) -> Piece {
    let hexes: Vec<[usize; 8]> = model.elements.iter().map(|e| e.nodes).collect();
    let body: Vec<usize> = model.elements.iter().map(|e| e.body).collect();
    let fields = solid_model_fields(model, u);
    solid_piece(&model.nodes, &hexes, &body, u, Some(&fields))
}

/// A series of `.vtu` files and the `.pvd` that collects them.
pub struct VtuSeries {
    pvd: PathBuf,
    dir: PathBuf,
    stem: String,
    entries: Vec<PvdEntry>,
}

impl VtuSeries {
    /// A series for `path` (`RUN.pvd`): creates the directory `RUN/` beside it.
    pub fn create(path: &Path) -> io::Result<Self> {
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .filter(|s| !s.is_empty())
            .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path has no file name"))?;
        let dir = path.with_file_name(&stem);
        std::fs::create_dir_all(&dir)?;
        Ok(VtuSeries {
            pvd: path.to_path_buf(),
            dir,
            stem,
            entries: Vec::new(),
        })
    }

    /// Write the datasets of one increment (the contact points only if given).
    pub fn step(&mut self, increment: usize, t: f64, mesh: &Piece, contact: Option<&Piece>) -> io::Result<()> {
        let parts = [("", Some(mesh)), ("contact_", contact)];
        for (part, (kind, piece)) in parts.into_iter().enumerate() {
            let Some(piece) = piece else { continue };
            let name = format!("{}_{kind}{increment:06}.vtu", self.stem);
            let mut w = BufWriter::new(std::fs::File::create(self.dir.join(&name))?);
            write_vtu(&mut w, piece)?;
            w.flush()?;
            self.entries.push(PvdEntry {
                t,
                part,
                file: format!("{}/{name}", self.stem),
            });
        }
        Ok(())
    }

    /// Write the `.pvd` collection of the steps written so far.
    pub fn finish(&self) -> io::Result<()> {
        let mut f = AtomicFile::create(&self.pvd)?;
        write_pvd(&mut f, &self.entries)?;
        f.commit()?;
        Ok(())
    }

    /// Number of increments written.
    pub fn steps(&self) -> usize {
        self.entries.iter().filter(|e| e.part == 0).count()
    }
}

/// The observer that writes a [`VtuSeries`] every `every`-th converged increment and the
/// last one.
pub struct VtuSink {
    series: VtuSeries,
    every: usize,
    name: String,
    /// The last converged increment if it has not been written yet.
    pending: Option<Pending>,
    model: Option<AnyModel>,
}

/// An increment kept until `finish` (its increment number, `t`, displacements and contact
/// points in 2D and 3D).
type Pending = (usize, f64, Vec<f64>, Vec<ContactPointRecord>, Vec<SurfacePointRecord>);

impl VtuSink {
    /// A sink writing `path` (`.pvd`) and the directory beside it; `every` ≥ 1.
    pub fn create(path: &Path, every: usize) -> io::Result<Self> {
        Ok(VtuSink {
            series: VtuSeries::create(path)?,
            every: every.max(1),
            name: path.display().to_string(),
            pending: None,
            model: None,
        })
    }

    fn err(&self, e: io::Error) -> ObserverError {
        ObserverError::new(&self.name, e)
    }

    fn write(
        &mut self,
        model: ModelRef<'_>,
        increment: usize,
        t: f64,
        u: &[f64],
        (contact, surface): (&[ContactPointRecord], &[SurfacePointRecord]),
    ) -> io::Result<()> {
        let (mesh, contact) = match model {
            ModelRef::Plane(model) => (
                model_piece(model, u),
                (!model.contacts.is_empty()).then(|| contact_piece(contact)),
            ),
            ModelRef::Solid(model) => (
                solid_model_piece(model, u),
                (!model.surface_contacts.is_empty()).then(|| surface_contact_piece(surface)),
            ),
        };
        self.series.step(increment, t, &mesh, contact.as_ref())
    }
}

impl Observer for VtuSink {
    fn start(&mut self, model: ModelRef<'_>, _info: &RunInfo) -> Result<(), ObserverError> {
        self.model = Some(model.to_owned());
        Ok(())
    }

    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        if rec.increment.is_multiple_of(self.every) {
            self.pending = None;
            self.write(view.model, rec.increment, rec.t, view.u, (view.contact, view.surface))
                .map_err(|e| self.err(e))
        } else {
            let (contact, surface) = (view.contact.to_vec(), view.surface.to_vec());
            self.pending = Some((rec.increment, rec.t, view.u.to_vec(), contact, surface));
            Ok(())
        }
    }

    fn finish(&mut self, _outcome: &Outcome) -> Result<(), ObserverError> {
        if let (Some((increment, t, u, contact, surface)), Some(model)) = (self.pending.take(), self.model.take()) {
            self.write(model.view(), increment, t, &u, (&contact, &surface))
                .map_err(|e| self.err(e))?;
        }
        self.series.finish().map_err(|e| self.err(e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::material::{lame, Material};
    use crate::element::material3d::stress_voigt;
    use crate::element::quad::ElementKind;
    use crate::model::box_mesh::BoxMesh;
    use crate::model::{Body, Element, SolidKind};
    use crate::record::vtu::file::Values;
    use nalgebra::{Matrix3, Vector3};

    /// A 3D model's VTU cells carry the centre fields: on a homogeneous state `x = F X` of a
    /// 2×1×2 box of EAS hexahedra (neo-Hooke, E = 200, ν = 0.3), every cell's
    /// `cauchy_stress` is `J⁻¹ F S Fᵀ` of the material at `E = ½(FᵀF − I)` to 1e-10 relative.
    #[test]
    fn hexahedra_carry_the_cauchy_stress_of_a_homogeneous_state() {
        let mesh = BoxMesh::new([0.0; 3], [2.0, 1.0, 1.5], [2, 1, 2], [1.0, 1.0, 1.3]);
        let (lambda, mu) = lame(200.0, 0.3);
        let material = Material::NeoHookean { lambda, mu };
        let model = Model::<Solid> {
            nodes: mesh.nodes.clone(),
            elements: mesh.hexes.iter().map(|&h| Element { nodes: h, body: 0 }).collect(),
            bodies: vec![Body {
                name: "block".into(),
                material,
                kind: SolidKind::from_element(ElementKind::Q4EasSafe),
                kinematics: (),
                first_node: 0,
                node_count: mesh.nodes.len(),
                node_sets: mesh.node_sets,
                faces: mesh.faces,
            }],
            ..Model::default()
        };
        let fm = Matrix3::new(0.96, 0.03, 0.0, -0.02, 1.04, 0.01, 0.05, 0.0, 0.99);
        let u: Vec<f64> = (mesh.nodes.iter())
            .flat_map(|p| {
                let x = Vector3::from(*p);
                let d = fm * x - x;
                [d[0], d[1], d[2]]
            })
            .collect();
        let e = 0.5 * (fm.transpose() * fm - Matrix3::identity());
        let mut ev = stress_voigt(&e);
        for a in 3..6 {
            ev[a] *= 2.0;
        }
        let (s, _) = material.stress_tangent_3d(&ev).unwrap();
        let st = Matrix3::new(s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2]);
        let sig = fm * st * fm.transpose() / fm.determinant();
        let piece = solid_model_piece(&model, &u);
        let cauchy = piece.cell_data.iter().find(|a| a.name == "cauchy_stress").unwrap();
        let Values::F64(v) = &cauchy.values else {
            panic!("f64 values")
        };
        assert_eq!((cauchy.components, v.len()), (9, 9 * model.elements.len()));
        for cell in v.chunks(9) {
            for (k, c) in cell.iter().enumerate() {
                let want = sig[(k / 3, k % 3)];
                assert!((c - want).abs() < 1e-10 * sig.norm(), "σ{k}: {c} vs {want}");
            }
        }
        let names: Vec<&str> = piece.cell_data.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(names, ["cauchy_stress", "green_lagrange_strain", "von_mises", "body"]);
    }
}
