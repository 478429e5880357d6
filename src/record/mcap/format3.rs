//! What one converged increment becomes in a format-3 recording, apart from `/increment` and
//! `/crossing` (written as they are): one `/contact` message of arrays per pair, with slave
//! nodes that stay out of reach left out ([`crate::record::mcap::sink::OutOfReach`]); `/pressure` and
//! `/positions` at the increments that have positions; the Foxglove scene at the increments
//! that have one; and `/log` twice (contrail's and `foxglove.Log`). Shared by the MCAP sink
//! and `contrail convert`, so that a converted recording is the one the sink would write.

use crate::record::interface::InterfaceRecord;
use crate::record::mcap::arrays::{ContactColumns, PressureColumns};
use crate::record::mcap::foxglove::{self, SceneEncoder, SceneView};
use crate::record::mcap::foxglove3d::{SolidSceneEncoder, SolidSceneView};
use crate::record::mcap::out::{McapOut, OutError};
use crate::record::mcap::schemas;
use crate::record::messages::{ModelRecord, PackedPositions, PositionsMessage};
use crate::record::packed_positions::PositionsContent;
use crate::record::pressure::PressureRecord;
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
    pair_names: Vec<String>,
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
        Format3Writer {
            thin_out_of_reach,
            out_of_reach: model.contacts.iter().map(|c| vec![false; c.slaves.len()]).collect(),
            is_node: (model.contacts.iter())
                .map(|c| c.slaves.iter().map(|s| node_of_label(s).is_some()).collect())
                .collect(),
            pair_names: model.contacts.iter().map(|c| c.name.clone()).collect(),
            take: Vec::new(),
            scene: SceneEncoder::new(model),
            solid_scene: (model.dim == Some(3)).then(|| SolidSceneEncoder::new(model)),
            scene_name: scene_name.to_string(),
            positions: PositionsContent::default(),
        }
    }

    /// Keep `content` of the positions. A slave node whose positions are not written bit for
    /// bit is never left out of `/contact` (readers restore a left-out entry from them).
    pub fn keep_positions(&mut self, model: &ModelRecord, content: PositionsContent) {
        for (flags, c) in self.is_node.iter_mut().zip(&model.contacts) {
            for (flag, s) in flags.iter_mut().zip(&c.slaves) {
                *flag = node_of_label(s).is_some_and(|n| content.exact_for(n));
            }
        }
        self.positions = content;
    }

    /// The `/contact` messages of increment `increment` (one per pair, its points in the
    /// order given, which is slave order): `positions_now` says whether the increment has `/positions` (only then
    /// can a point out of reach be left out and restored by readers).
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
                if self.thin_out_of_reach && positions_now && out_now && was_out && node {
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
