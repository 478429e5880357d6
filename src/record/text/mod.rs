//! Plain-text sinks: the load–displacement CSV and every record as JSON lines.

pub mod csv;
pub mod jsonl;
