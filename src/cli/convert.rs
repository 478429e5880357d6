//! `contrail convert OLD.mcap NEW.mcap`: a recording of an older format written again in the
//! current one (format 3, with the Foxglove channels).

use super::out::outln;
use super::BadInput;
use contrail::analysis::convert::{convert as rewrite, ConvertOptions};
use contrail::analysis::recording::Recording;
use contrail::record::atomic_file::AtomicFile;
use contrail::record::mcap::out::{ChunkCompression, Compression};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct ConvertArgs {
    /// A recording of any format this build reads.
    pub old: PathBuf,
    /// Where to write it in the current format.
    pub new: PathBuf,
    /// Compression of the chunks.
    #[arg(long, value_enum, value_name = "KIND", default_value_t = ChunkCompression::Zstd)]
    pub compression: ChunkCompression,
    /// zstd level of the chunks: 1–19 (higher: smaller files, slower to write) or −1 to −7
    /// (zstd's fast levels: faster, larger).
    #[arg(long, value_name = "LEVEL", default_value_t = 1, allow_negative_numbers = true,
          value_parser = clap::value_parser!(i32).range(-7..=19))]
    pub level: i32,
    /// Leave out the message indexes (a smaller file; readers work without them).
    #[arg(long)]
    pub no_index: bool,
    #[command(flatten)]
    pub scene: super::run::SceneArgs,
}

pub fn convert(a: ConvertArgs) -> anyhow::Result<ExitCode> {
    let name = a.old.display().to_string();
    if a.old == a.new {
        return Err(BadInput(format!("{name}: write the converted recording to another file")).into());
    }
    let r = Recording::open(&a.old).map_err(|e| BadInput(e.to_string()))?;
    let out = AtomicFile::create(&a.new).map_err(|e| BadInput(format!("{}: cannot create: {e}", a.new.display())))?;
    let opts = ConvertOptions {
        compression: Compression {
            kind: a.compression,
            zstd_level: a.level,
        },
        message_indexes: !a.no_index,
        scene: a.scene.scene_every,
    };
    let (out, rep) = rewrite(&r, out, &opts).map_err(|e| anyhow::anyhow!("{}: {e}", a.new.display()))?;
    out.commit()
        .map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", a.new.display()))?;
    outln!(
        "converted    {name} (format {} → {})",
        rep.from_version,
        contrail::record::mcap::schemas::FORMAT_VERSION
    )?;
    outln!("increments   {}, {} Foxglove scenes", rep.increments, rep.scenes)?;
    outln!("written      {}", a.new.display())?;
    Ok(ExitCode::SUCCESS)
}
