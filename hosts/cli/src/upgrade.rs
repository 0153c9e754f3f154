//! `umbra arch upgrade`, `umbra scene upgrade`, `umbra sweep upgrade`: a
//! file written for an earlier format, rewritten for the current one (the
//! format stated, the keys added since with the values that keep what the
//! file meant, each with its meaning as a comment). The upgraded text goes
//! to stdout, or with `--in-place` replaces the file (through a new file
//! renamed over it, and only when it changes).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Subcommand;
use umbra_sim::Arch;
use umbra_sim::experiment::study::SweepFile;
use umbra_sim::input::format::{SCENE, SWEEP};
use umbra_sim::input::limits::Limits;
use umbra_sim::world::scene::Scene;

use crate::say::say;

/// The file to upgrade.
#[derive(clap::Args, Debug)]
pub(crate) struct UpgradeArgs {
    /// The file.
    file: PathBuf,
    /// Replace the file with its upgraded text, instead of printing it.
    #[arg(long)]
    in_place: bool,
}

/// `umbra sweep …`.
#[derive(Subcommand, Debug)]
pub(super) enum FileCommand {
    /// Rewrite the file for the current file format: the format stated,
    /// every comment and value as it was.
    Upgrade(UpgradeArgs),
}

/// The kinds of file an upgrade reads.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Kind {
    /// An architecture file.
    Arch,
    /// A scene file.
    Scene,
    /// A sweep file.
    Sweep,
}

/// Upgrade `args.file`, a file of `kind`: it must load as it is first.
pub(crate) fn upgrade(kind: Kind, args: &UpgradeArgs, limits: &Limits) -> Result<()> {
    let path = &args.file;
    let bytes = limits.read_text_file(path).with_context(|| format!("{}", path.display()))?;
    let text = String::from_utf8(bytes).with_context(|| format!("{}: not UTF-8 text", path.display()))?;
    let name = path.display().to_string();
    let new = match kind {
        Kind::Arch => Arch::upgrade(&text, &name)?,
        Kind::Scene => {
            Scene::load(path, limits)?;
            SCENE.upgrade(&text, &[]).map_err(|e| anyhow::anyhow!("{name}: {e}"))?
        }
        Kind::Sweep => {
            SweepFile::open(&name, limits)?.spec(limits)?;
            SWEEP.upgrade(&text, &[]).map_err(|e| anyhow::anyhow!("{name}: {e}"))?
        }
    };
    if !args.in_place {
        say!("{}", new.trim_end());
        return Ok(());
    }
    if new == text {
        eprintln!("{name}: already in the current format; left as it is");
        return Ok(());
    }
    replace(path, &new)?;
    eprintln!("{name}: upgraded in place");
    Ok(())
}

/// Write `text` to a new file beside `path`, then rename it over `path`:
/// the file is whole, old or new, whenever it is read.
fn replace(path: &Path, text: &str) -> Result<()> {
    let file = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let new = path.with_file_name(format!(".{file}.upgrading"));
    std::fs::write(&new, text).with_context(|| format!("{}", new.display()))?;
    std::fs::rename(&new, path).with_context(|| format!("{}", path.display()))
}
