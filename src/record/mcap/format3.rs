//! What one converged increment becomes in a format-3 recording, apart from `/increment` and
//! `/crossing` (written as they are): one `/contact` message of arrays per pair and one
//! `/surface_contact` message per 3D pair, with slave nodes that stay out of reach left out
//! ([`crate::record::mcap::sink::OutOfReach`]); `/pressure` and
//! `/positions` at the increments that have positions; the Foxglove scene at the increments
//! that have one; and `/log` twice (contrail's and `foxglove.Log`). Shared by the MCAP sink
//! and `contrail convert`, so that a converted recording is the one the sink would write.

use crate::record::interface::InterfaceRecord;
use crate::record::mcap::arrays::{ContactColumns, PressureColumns};
use crate::record::mcap::foxglove::{self, SceneEncoder, SceneView};
use crate::record::mcap::foxglove3d::{SolidSceneEncoder, SolidSceneView};
use crate::record::mcap::out::{McapOut, OutError};
use crate::record::mcap::schemas;
use crate::record::mcap::surface_arrays::SurfaceContactArrays;
use crate::record::messages::{ModelRecord, PackedPositions, PositionsMessage};
use crate::record::packed_positions::PositionsContent;
use crate::record::pressure::PressureRecord;
use crate::record::surface_contact::SurfacePointRecord;
use crate::record::{ContactPointRecord, LogRecord};
use std::io::{Seek, Write};

/// The node of a slave labelled `node N` (see [`crate::model::Model::slave_label`]).
pub fn node_of_label(label: &str) -> Option<usize> {
    label.strip_prefix("node ")?.parse().ok()
}

/// Writes the per-increment messages of one run (see the module documentation).
pub struct Format3Writer {
    /// Leave out the slave nodes that stay out of reach.
    thin_out_of_reach: bool,
    /// Per pair and slave: the last `/contact` entry written was out of reach.
    out_of_reach: Vec<Vec<bool>>,
    /// Per pair: whether each slave is a node (only nodes are thinned).
    is_node: Vec<Vec<bool>>,
    /// Per pair: whether each slave is a node whose position `/positions` holds bit for bit.
    exact: Vec<Vec<bool>>,
    pair_names: Vec<String>,
    /// Per 3D pair: its name and whether `/positions` holds each slave's position bit for bit.
    surface_pairs: Vec<(String, Vec<bool>)>,
    /// Keep every position a record has: at an increment without `/positions`, leave out
    /// only a point whose position is NaN already (`contrail convert`); otherwise the
    /// positions of such increments are not kept (the sink: the user's choice).
    lossless: bool,
    /// Indices of the points of one pair written in one message (reused).
    take: Vec<usize>,
    scene: SceneEncoder,
    /// The scene of a 3D model (then `scene` draws nothing).
    solid_scene: Option<SolidSceneEncoder>,
    scene_name: String,
    /// What `/positions` keeps (every node in double precision unless the user chose).
    positions: PositionsContent,
}

impl Format3Writer {
    pub fn new(model: &ModelRecord, scene_name: &str, thin_out_of_reach: bool) -> Self {
        let is_node: Vec<Vec<bool>> = (model.contacts.iter())
            .map(|c| c.slaves.iter().map(|s| node_of_label(s).is_some()).collect())
            .collect();
        Format3Writer {
            thin_out_of_reach,
            out_of_reach: model.contacts.iter().map(|c| vec![false; c.slaves.len()]).collect(),
            exact: is_node.clone(),
            is_node,
            pair_names: model.contacts.iter().map(|c| c.name.clone()).collect(),
            surface_pairs: (model.surface_contacts.iter())
                .map(|c| (c.name.clone(), vec![true; c.slave_nodes.len()]))
                .collect(),
            lossless: false,
            take: Vec::new(),
            scene: SceneEncoder::new(model),
            solid_scene: (model.dim == Some(3)).then(|| SolidSceneEncoder::new(model)),
            scene_name: scene_name.to_string(),
            positions: PositionsContent::default(),
        }
    }

    /// Write every position the records have (see `lossless`): a converted recording keeps
    /// what its source kept.
    pub fn lossless(mut self) -> Self {
        self.lossless = true;
        self
    }

    /// Keep `content` of the positions. At an increment with `/positions`, a slave node whose
    /// position is not written there bit for bit is not left out of the contact channels
    /// (readers restore a left-out entry with the position `/positions` holds).
    pub fn keep_positions(&mut self, model: &ModelRecord, content: PositionsContent) {
        for (flags, c) in self.exact.iter_mut().zip(&model.contacts) {
            for (flag, s) in flags.iter_mut().zip(&c.slaves) {
                *flag = node_of_label(s).is_some_and(|n| content.exact_for(n));
            }
        }
        for ((_, flags), c) in self.surface_pairs.iter_mut().zip(&model.surface_contacts) {
            for (flag, &n) in flags.iter_mut().zip(&c.slave_nodes) {
                *flag = content.exact_for(n);
            }
        }
        self.positions = content;
    }

    /// The `/contact` messages of increment `increment` (one per pair, its points in the
    /// order given, which is slave order): `positions_now` says whether the increment has
    /// `/positions`. A node slave that stays out of reach is left out where that increment
    /// holds its position bit for bit, and at every increment without `/positions` (its
    /// record is its position, which the user chose not to keep there).
    pub fn contact<W: Write + Seek>(
        &mut self,
        out: &mut McapOut<W>,
        increment: usize,
        t: f64,
        points: &[ContactPointRecord],
        positions_now: bool,
    ) -> Result<(), OutError> {
        for pair in 0..self.pair_names.len() {
            self.take.clear();
            for (k, p) in points.iter().enumerate().filter(|(_, p)| p.pair == pair) {
                let out_now = p.segment.is_none();
                let flags = &mut self.out_of_reach[pair];
                let was_out = flags.get(p.slave).copied().unwrap_or(false);
                if let Some(f) = flags.get_mut(p.slave) {
                    *f = out_now;
                }
                let node = self.is_node[pair].get(p.slave).copied().unwrap_or(false);
                let exact = self.exact[pair].get(p.slave).copied().unwrap_or(false);
                if out_now && was_out && node && self.restorable(exact, positions_now, &p.position) {
                    continue;
                }
                self.take.push(k);
            }
            let msg = ContactColumns {
                increment,
                t,
                pair,
                pair_name: &self.pair_names[pair],
                points,
                take: &self.take,
            };
            out.put(schemas::CONTACT, &msg)?;
        }
        Ok(())
    }

    /// The `/surface_contact` messages of an increment of a 3D model: one per 3D pair, with
    /// the displacement `offsets[pair]` of its rigid master, its points among `points` in
    /// their order (slave order). A point out of reach since the last converged increment
    /// ([`SurfacePointRecord::is_bare_out_of_reach`]) is left out under the rule of
    /// [`Format3Writer::contact`]; readers put back [`SurfacePointRecord::out_of_reach`].
    pub fn surface_contact<W: Write + Seek>(
        &mut self,
        out: &mut McapOut<W>,
        (increment, t): (usize, f64),
        offsets: &[[f64; 3]],
        points: &[SurfacePointRecord],
        positions_now: bool,
    ) -> Result<(), OutError> {
        for (pair, (name, exact)) in self.surface_pairs.iter().enumerate() {
            let kept = points.iter().filter(|p| p.pair == pair).filter(|p| {
                let exact = exact.get(p.slave).copied().unwrap_or(false);
                !(p.is_bare_out_of_reach() && self.restorable(exact, positions_now, &p.position))
            });
            let offset = offsets.get(pair).copied().unwrap_or([0.0; 3]);
            let msg = SurfaceContactArrays::of((increment, t), (pair, name), offset, kept);
            out.put(schemas::SURFACE_CONTACT, &msg)?;
        }
        Ok(())
    }

    /// Whether a point out of reach since the last increment may be left out: thinning is on
    /// and a reader puts back what the point had — its position bit for bit (`exact` at an
    /// increment with `/positions`), or no position where none is kept (an increment without
    /// `/positions`; converting, only a record that had none either).
    fn restorable(&self, exact: bool, positions_now: bool, position: &[f64]) -> bool {
        let unkept = !positions_now && (!self.lossless || position.iter().any(|x| !x.is_finite()));
        self.thin_out_of_reach && ((positions_now && exact) || unkept)
    }

    /// The `/pressure` and `/positions` messages of an increment.
    pub fn positions<W: Write + Seek>(
        &mut self,
        out: &mut McapOut<W>,
        positions: &PositionsMessage,
        pressure: &[PressureRecord],
    ) -> Result<(), OutError> {
        for p in pressure {
            out.put(schemas::PRESSURE, &PressureColumns(p))?;
        }
        out.put_with(schemas::POSITIONS, |buf, _| {
            PackedPositions::write_json(buf, positions, &self.positions).map_err(OutError::from)
        })
    }

    /// The `/interface` messages of an increment (written with its `/positions`).
    pub fn interfaces<W: Write + Seek>(
        &mut self,
        out: &mut McapOut<W>,
        interfaces: &[InterfaceRecord],
    ) -> Result<(), OutError> {
        for i in interfaces {
            out.put(schemas::INTERFACE, i)?;
        }
        Ok(())
    }

    /// The reference mesh for Foxglove (once, at the start).
    pub fn reference<W: Write + Seek>(&mut self, out: &mut McapOut<W>) -> Result<(), OutError> {
        let (scene, solid) = (&self.scene, &self.solid_scene);
        out.put_with(schemas::FOXGLOVE_REFERENCE, |buf, now| {
            match solid {
                Some(s) => s.write_reference(buf, now),
                None => scene.write_reference(buf, now),
            }
            Ok(())
        })
    }

    /// The Foxglove scene of an increment of a 3D model (nothing for a plane model).
    pub fn solid_scene<W: Write + Seek>(
        &mut self,
        out: &mut McapOut<W>,
        view: &SolidSceneView,
    ) -> Result<(), OutError> {
        let Some(scene) = &self.solid_scene else {
            return Ok(());
        };
        out.put_with(schemas::FOXGLOVE_SCENE, |buf, now| {
            scene.write(buf, view, now);
            Ok(())
        })
    }

    /// The Foxglove scene of an increment.
    pub fn scene<W: Write + Seek>(&mut self, out: &mut McapOut<W>, view: &SceneView) -> Result<(), OutError> {
        let scene = &self.scene;
        out.put_with(schemas::FOXGLOVE_SCENE, |buf, now| {
            scene.write(buf, view, now);
            Ok(())
        })
    }

    /// A log message, on `/log` and as `foxglove.Log`.
    pub fn log<W: Write + Seek>(&mut self, out: &mut McapOut<W>, rec: &LogRecord) -> Result<(), OutError> {
        out.put(schemas::LOG, rec)?;
        let name = &self.scene_name;
        out.put_with(schemas::FOXGLOVE_LOG, |buf, now| {
            foxglove::log(buf, rec, name, now);
            Ok(())
        })
    }
}
