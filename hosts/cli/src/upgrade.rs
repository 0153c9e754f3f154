//! `umbra arch upgrade`, `umbra scene upgrade`, `umbra sweep upgrade`: a
//! file written for an earlier format, rewritten for the current one (the
//! format stated, the keys added since with the values that keep what the
//! file meant, each with its meaning as a comment). The upgraded text goes
//! to stdout, or with `--in-place` replaces the file (through a new file
//! renamed over it, and only when it changes), keeping its permissions,
//! owner and line endings, at a link's target.

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
    let new = with_line_endings_of(&new, &text);
    if new == text {
        eprintln!("{name}: already in the current format; left as it is");
        return Ok(());
    }
    let target = replace(path, &new)?;
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
        eprintln!("{name}: upgraded in place, at the link's target {}", target.display());
    } else {
        eprintln!("{name}: upgraded in place");
    }
    Ok(())
}

/// Replace the file at `path` with `text`, keeping what the file was: a
/// link is followed to its target (the link stays a link), the new file
/// is created beside the target under a fresh random name, exclusively
/// (never through a link planted there), with the original's permissions
/// and owner, flushed to the disk, then renamed over the
/// target: the file is whole, old or new, whenever it is read (`text` has
/// the original's line endings already). A file the
/// user may not write (its write bit off, or not theirs to write) is
/// refused, naming it.
fn replace(path: &Path, text: &str) -> Result<PathBuf> {
    use std::io::Write as _;
    let target = std::fs::canonicalize(path).with_context(|| format!("{}", path.display()))?;
    let meta = std::fs::metadata(&target).with_context(|| format!("{}", target.display()))?;
    if !meta.is_file() {
        anyhow::bail!("{}: not a regular file; --in-place replaces a file", target.display());
    }
    if meta.permissions().readonly() {
        anyhow::bail!(
            "{}: read-only; make it writable to upgrade it in place, or print the upgrade without --in-place",
            target.display()
        );
    }
    std::fs::OpenOptions::new().write(true).open(&target).with_context(|| {
        format!("{}: cannot be written; --in-place replaces only a file you may write", target.display())
    })?;
    let dir = target.parent().unwrap_or_else(|| Path::new("."));
    let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let mut new = tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(".upgrading")
        .tempfile_in(dir)
        .with_context(|| format!("{}: a new file beside it", target.display()))?;
    new.as_file().set_permissions(meta.permissions()).with_context(|| format!("{}", new.path().display()))?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let mine = new.as_file().metadata().with_context(|| format!("{}", new.path().display()))?;
        if (mine.uid(), mine.gid()) != (meta.uid(), meta.gid()) {
            std::os::unix::fs::fchown(new.as_file(), Some(meta.uid()), Some(meta.gid())).with_context(|| {
                format!(
                    "{}: cannot keep its owner {}:{}; upgrade it as its owner",
                    target.display(),
                    meta.uid(),
                    meta.gid()
                )
            })?;
        }
    }
    new.write_all(text.as_bytes())
        .and_then(|()| new.as_file().sync_all())
        .with_context(|| format!("{}", new.path().display()))?;
    new.persist(&target).map_err(|e| e.error).with_context(|| format!("{}", target.display()))?;
    Ok(target)
}

/// `text` with the line endings of `original`: CRLF throughout when the
/// original's first line ends in CRLF, else as it is.
fn with_line_endings_of(text: &str, original: &str) -> String {
    let crlf = original.find('\n').is_some_and(|k| original[..k].ends_with('\r'));
    if crlf { text.replace("\r\n", "\n").replace('\n', "\r\n") } else { text.to_owned() }
}
