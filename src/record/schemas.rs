//! The channels of a contrail MCAP recording and the JSON Schemas of their messages,
//! generated from the Rust types (schemars). The same text is embedded in every recording
//! and checked into `schemas/` (`CONTRAIL_BLESS=1 cargo test --test recording_schemas`
//! rewrites those files; the test fails when they and the types disagree).

use super::messages::{ContactPointMessage, CrossingMessage, ModelRecord, PositionsMessage};
use super::pressure::PressureRecord;
use super::{IncrementRecord, IterationRecord, LogRecord, Outcome};
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
    schema: fn() -> schemars::Schema,
}

impl ChannelSpec {
    /// The JSON Schema text (pretty-printed, newline-terminated).
    pub fn schema_text(&self) -> String {
        let mut s = serde_json::to_string_pretty(&(self.schema)()).unwrap_or_else(|_| "{}".into());
        s.push('\n');
        s
    }
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

/// MCAP header profile of a contrail recording.
pub const PROFILE: &str = "contrail";
/// Name of the MCAP metadata record with the run's facts.
pub const METADATA_NAME: &str = "contrail.run";
/// Version of the recording layout (channels and their message types).
pub const FORMAT_VERSION: &str = "2";
/// Format versions this build reads (1: every `/contact` point of every increment; 2: points
/// that stay out of reach left out, see [`crate::record::mcap_sink::OutOfReach`]).
pub const READABLE_VERSIONS: &[&str] = &["1", "2"];

/// Every channel, in the order they are registered in a recording.
pub const CHANNELS: &[ChannelSpec] = &[
    ChannelSpec {
        topic: MODEL,
        schema_name: "contrail.Model",
        file: "model.schema.json",
        description: "static model: mesh topology, rigid surfaces as polylines, contact pairs (once, first)",
        schema: || schemars::schema_for!(ModelRecord),
    },
    ChannelSpec {
        topic: INCREMENT,
        schema_name: "contrail.Increment",
        file: "increment.schema.json",
        description: "one per converged increment: load level, step, iterations, cut-backs, residuals, monitor, reactions, wall time",
        schema: || schemars::schema_for!(IncrementRecord),
    },
    ChannelSpec {
        topic: ITERATION,
        schema_name: "contrail.Iteration",
        file: "iteration.schema.json",
        description: "one per Newton iteration, failed attempts included: residual and energy norms, line search, active-set changes",
        schema: || schemars::schema_for!(IterationRecord),
    },
    ChannelSpec {
        topic: CONTACT,
        schema_name: "contrail.ContactPoint",
        file: "contact_point.schema.json",
        description: "one per converged increment and slave point (a slave node out of reach: only where it leaves reach; readers restore the rest, format 2): segment, previous segment, xi, anchor, gap, forces, state",
        schema: || schemars::schema_for!(ContactPointMessage),
    },
    ChannelSpec {
        topic: CROSSING,
        schema_name: "contrail.Crossing",
        file: "crossing.schema.json",
        description: "one per segment crossing: A, B, xi_A, xi_B, delta rho, traction before and after transfer",
        schema: || schemars::schema_for!(CrossingMessage),
    },
    ChannelSpec {
        topic: POSITIONS,
        schema_name: "contrail.Positions",
        file: "positions.schema.json",
        description: "current node coordinates and rigid-body offsets (every N-th increment and the last)",
        schema: || schemars::schema_for!(PositionsMessage),
    },
    ChannelSpec {
        topic: LOG,
        schema_name: "contrail.Log",
        file: "log.schema.json",
        description: "warnings (cut-backs) and errors (failure, interruption) for humans",
        schema: || schemars::schema_for!(LogRecord),
    },
    ChannelSpec {
        topic: OUTCOME,
        schema_name: "contrail.Outcome",
        file: "outcome.schema.json",
        description: "how the run ended: completed, failed (where, why, last residuals) or interrupted (last message)",
        schema: || schemars::schema_for!(Outcome),
    },
    ChannelSpec {
        topic: PRESSURE,
        schema_name: "contrail.Pressure",
        file: "pressure.schema.json",
        description: "contact pressure against arc length along the master, one per node-slave pair, at the increments that have /positions",
        schema: || schemars::schema_for!(PressureRecord),
    },
];

/// The channel of a topic.
pub fn channel(topic: &str) -> Option<&'static ChannelSpec> {
    CHANNELS.iter().find(|c| c.topic == topic)
}

/// Write every schema into `dir`.
pub fn write_all(dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for c in CHANNELS {
        std::fs::write(dir.join(c.file), c.schema_text())?;
    }
    Ok(())
}

/// Files in `dir` that are missing or differ from the generated schemas.
pub fn stale(dir: &Path) -> Vec<String> {
    CHANNELS
        .iter()
        .filter(|c| std::fs::read_to_string(dir.join(c.file)).ok().as_deref() != Some(c.schema_text().as_str()))
        .map(|c| c.file.to_string())
        .collect()
}
