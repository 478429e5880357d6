//! The channels of a contrail MCAP recording and the JSON Schemas of their messages.
//! contrail's own schemas are generated from the Rust types (schemars) and carry the format
//! version in their `$id`; the same text is embedded in every recording and checked into
//! `schemas/` (`CONTRAIL_BLESS=1 cargo test --test recording_schemas` rewrites those files;
//! the test fails when they and the types disagree). The schemas of format 2 stay in
//! `schemas/format2/` for validating older recordings. The Foxglove channels embed the
//! published schemas of `@foxglove/schemas` (see [`crate::record::mcap::foxglove`]).

use crate::record::interface::InterfaceRecord;
use crate::record::mcap::arrays::{ContactArrays, PressureArrays};
use crate::record::mcap::foxglove::{FOXGLOVE_LOG_SCHEMA, FOXGLOVE_SCENE_SCHEMA};
use crate::record::mcap::surface_arrays::SurfaceContactArrays;
use crate::record::messages::{CrossingMessage, ModelRecord, PackedPositions};
use crate::record::{IncrementRecord, IterationRecord, LogRecord, Outcome};
use std::path::Path;

/// One channel of a recording.
#[derive(Debug, Clone, Copy)]
pub struct ChannelSpec {
    /// MCAP topic.
    pub topic: &'static str,
    /// MCAP schema name.
    pub schema_name: &'static str,
    /// File in `schemas/` that holds the schema.
    pub file: &'static str,
    pub description: &'static str,
    schema: Source,
}

/// Where a channel's schema comes from.
#[derive(Debug, Clone, Copy)]
enum Source {
    /// Generated from a contrail type.
    Generated(fn() -> schemars::Schema),
    /// Published by someone else (Foxglove), embedded as it is.
    Published(&'static str),
}

impl ChannelSpec {
    /// The JSON Schema text (contrail's: pretty-printed, newline-terminated, with the format
    /// version in its `$id`).
    pub fn schema_text(&self) -> String {
        match self.schema {
            Source::Generated(f) => {
                let mut schema = f();
                schema.insert("$id".into(), schema_id(self.file).into());
                let mut s = serde_json::to_string_pretty(&schema).unwrap_or_else(|_| "{}".into());
                s.push('\n');
                s
            }
            Source::Published(text) => text.to_string(),
        }
    }

    /// A channel of contrail's own (not a Foxglove one).
    pub fn is_contrail(&self) -> bool {
        matches!(self.schema, Source::Generated(_))
    }
}

/// The `$id` of a contrail schema: its file and the format version.
pub fn schema_id(file: &str) -> String {
    format!("urn:contrail:recording:format-{FORMAT_VERSION}:{file}")
}

pub const MODEL: &str = "/model";
pub const INCREMENT: &str = "/increment";
pub const ITERATION: &str = "/iteration";
pub const CONTACT: &str = "/contact";
pub const CROSSING: &str = "/crossing";
pub const POSITIONS: &str = "/positions";
pub const LOG: &str = "/log";
pub const OUTCOME: &str = "/outcome";
pub const PRESSURE: &str = "/pressure";
pub const INTERFACE: &str = "/interface";
pub const SURFACE_CONTACT: &str = "/surface_contact";
pub const FOXGLOVE_LOG: &str = "/foxglove/log";
pub const FOXGLOVE_SCENE: &str = "/foxglove/scene";
pub const FOXGLOVE_REFERENCE: &str = "/foxglove/reference";

/// MCAP header profile of a contrail recording.
pub const PROFILE: &str = "contrail";
/// Name of the MCAP metadata record with the run's facts.
pub const METADATA_NAME: &str = "contrail.run";
/// Version of the recording layout (channels and their message types).
pub const FORMAT_VERSION: &str = "3";
/// Format versions this build reads (1: one `/contact` message per point of every
/// increment; 2: points that stay out of reach left out, see
/// [`crate::record::mcap::sink::OutOfReach`]; 3: `/contact` and `/pressure` as one message
/// of arrays per increment and pair, `/positions` packed, Foxglove channels beside).
pub const READABLE_VERSIONS: &[&str] = &["1", "2", "3"];
/// Schema names of the format-3 `/contact` and `/pressure` messages (formats 1 and 2 have
/// `contrail.ContactPoint` and `contrail.Pressure`, one point or one profile of objects).
pub const CONTACT_ARRAYS: &str = "contrail.ContactArrays";
pub const PRESSURE_ARRAYS: &str = "contrail.PressureArrays";
/// Schema name of the format-3 `/positions` message (node coordinates packed as binary;
/// formats 1 and 2 have `contrail.Positions`, a list of pairs).
pub const PACKED_POSITIONS: &str = "contrail.PackedPositions";
/// Schema name of `/surface_contact` (3D contact points, format 3).
pub const SURFACE_CONTACT_ARRAYS: &str = "contrail.SurfaceContactArrays";

/// Every channel, in the order they are registered in a recording.
pub const CHANNELS: &[ChannelSpec] = &[
    ChannelSpec {
        topic: MODEL,
        schema_name: "contrail.Model",
        file: "model.schema.json",
        description: "static model: mesh topology, rigid surfaces as polylines, contact pairs (once, first)",
        schema: Source::Generated(|| schemars::schema_for!(ModelRecord)),
    },
    ChannelSpec {
        topic: INCREMENT,
        schema_name: "contrail.Increment",
        file: "increment.schema.json",
        description: "one per converged increment: load level, step, iterations, cut-backs, residuals, monitor, reactions, wall time",
        schema: Source::Generated(|| schemars::schema_for!(IncrementRecord)),
    },
    ChannelSpec {
        topic: ITERATION,
        schema_name: "contrail.Iteration",
        file: "iteration.schema.json",
        description: "one per Newton iteration, failed attempts included: residual and energy norms, line search, active-set changes",
        schema: Source::Generated(|| schemars::schema_for!(IterationRecord)),
    },
    ChannelSpec {
        topic: CONTACT,
        schema_name: CONTACT_ARRAYS,
        file: "contact.schema.json",
        description: "one per converged increment and contact pair, every field an array over its slave points (slave nodes that stay out of reach left out where /positions holds them bit for bit and at increments without /positions; readers restore them): slave, segment, previous segment, xi, anchor, gap, forces, state, crossing, positions, normals, tangents",
        schema: Source::Generated(|| schemars::schema_for!(ContactArrays)),
    },
    ChannelSpec {
        topic: CROSSING,
        schema_name: "contrail.Crossing",
        file: "crossing.schema.json",
        description: "one per segment crossing: A, B, xi_A, xi_B, delta rho, traction before and after transfer",
        schema: Source::Generated(|| schemars::schema_for!(CrossingMessage)),
    },
    ChannelSpec {
        topic: POSITIONS,
        schema_name: PACKED_POSITIONS,
        file: "positions.schema.json",
        description: "current node coordinates (little-endian doubles, base64) and rigid-body offsets (every N-th increment and the last)",
        schema: Source::Generated(|| schemars::schema_for!(PackedPositions)),
    },
    ChannelSpec {
        topic: LOG,
        schema_name: "contrail.Log",
        file: "log.schema.json",
        description: "warnings (cut-backs) and errors (failure, interruption) for humans",
        schema: Source::Generated(|| schemars::schema_for!(LogRecord)),
    },
    ChannelSpec {
        topic: OUTCOME,
        schema_name: "contrail.Outcome",
        file: "outcome.schema.json",
        description: "how the run ended: completed, failed (where, why, last residuals) or interrupted (last message)",
        schema: Source::Generated(|| schemars::schema_for!(Outcome)),
    },
    ChannelSpec {
        topic: PRESSURE,
        schema_name: PRESSURE_ARRAYS,
        file: "pressure.schema.json",
        description: "contact pressure against arc length along the master, one per node-slave pair at the increments that have /positions, every field an array over the paired slave nodes",
        schema: Source::Generated(|| schemars::schema_for!(PressureArrays)),
    },
    ChannelSpec {
        topic: INTERFACE,
        schema_name: "contrail.Interface",
        file: "interface.schema.json",
        description: "one per two-pass contact pair at the increments that have /positions: both passes combined into the traction on the first pass's master face (each contact force once), totals and arrays over its nodes: node, s, position, normal, tributary, pressure, shear, state",
        schema: Source::Generated(|| schemars::schema_for!(InterfaceRecord)),
    },
    ChannelSpec {
        topic: SURFACE_CONTACT,
        schema_name: SURFACE_CONTACT_ARRAYS,
        file: "surface-contact.schema.json",
        description: "3D (node-to-surface) contact: one per converged increment and pair, every field an array over its slave nodes (those that stay out of reach left out as on /contact; readers restore them): slave, node, facet, previous facet, convective coordinates (xi1, xi2), gap, normal force, trial and returned covariant tractions, state, crossing, history lost, the history carried across a facet edge, positions, contact points, normals, forces; the rigid master's offset",
        schema: Source::Generated(|| schemars::schema_for!(SurfaceContactArrays)),
    },
    ChannelSpec {
        topic: FOXGLOVE_LOG,
        schema_name: "foxglove.Log",
        file: "foxglove/foxglove.Log.json",
        description: "/log as foxglove.Log, for Foxglove's Log panel",
        schema: Source::Published(FOXGLOVE_LOG_SCHEMA),
    },
    ChannelSpec {
        topic: FOXGLOVE_REFERENCE,
        schema_name: "foxglove.SceneUpdate",
        file: "foxglove/foxglove.SceneUpdate.json",
        description: "the reference mesh for Foxglove's 3D panel, once at the start (plane z = 0, y up)",
        schema: Source::Published(FOXGLOVE_SCENE_SCHEMA),
    },
    ChannelSpec {
        topic: FOXGLOVE_SCENE,
        schema_name: "foxglove.SceneUpdate",
        file: "foxglove/foxglove.SceneUpdate.json",
        description: "the model for Foxglove's 3D panel at the increments with a scene: deformed mesh, rigid surfaces, contact points coloured by state, a label (plane z = 0, y up)",
        schema: Source::Published(FOXGLOVE_SCENE_SCHEMA),
    },
];

/// The channel of a topic.
pub fn channel(topic: &str) -> Option<&'static ChannelSpec> {
    CHANNELS.iter().find(|c| c.topic == topic)
}

/// Write every generated schema into `dir`.
pub fn write_all(dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for c in CHANNELS.iter().filter(|c| c.is_contrail()) {
        std::fs::write(dir.join(c.file), c.schema_text())?;
    }
    Ok(())
}

/// Files in `dir` that are missing or differ from the schemas embedded in a recording.
pub fn stale(dir: &Path) -> Vec<String> {
    CHANNELS
        .iter()
        .filter(|c| std::fs::read_to_string(dir.join(c.file)).ok().as_deref() != Some(c.schema_text().as_str()))
        .map(|c| c.file.to_string())
        .collect()
}
