//! The command's printing: a closed stdout (the reader went away, as
//! `| head` does) stops the printing quietly and the run goes on to finish
//! its files; any other error writing stdout ends the command with an
//! error naming it.

use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Result, anyhow};
use umbra_sim::output::folder::{MANIFEST, Replaced, RunManifest};

/// Set once stdout is found closed.
static CLOSED: AtomicBool = AtomicBool::new(false);

/// Print one line.
///
/// # Errors
/// Writing stdout failed for another reason than a closed pipe.
pub(crate) fn line(args: std::fmt::Arguments<'_>) -> Result<()> {
    if CLOSED.load(Ordering::Relaxed) {
        return Ok(());
    }
    let mut out = std::io::stdout().lock();
    match out.write_fmt(args).and_then(|()| out.write_all(b"\n")).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
            CLOSED.store(true, Ordering::Relaxed);
            Ok(())
        }
        Err(e) => Err(anyhow!("stdout: {e}")),
        Ok(()) => Ok(()),
    }
}

/// Print a line (formatted as by `println!`), returning an error from the
/// enclosing function when stdout fails (see [`line()`]).
macro_rules! say {
    ($($t:tt)*) => {
        $crate::say::line(format_args!($($t)*))?
    };
}
pub(crate) use say;

/// How much a command prints: every figure (a subcommand of its own), or
/// the few a person reads first, in lines of at most [`BRIEF_WIDTH`]
/// columns (the main job's), the rest left in the files it wrote.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Style {
    /// Every figure and every file written.
    Full,
    /// The headline figures and where the files went.
    Brief,
}

/// The widest line the brief style prints, in columns.
pub(crate) const BRIEF_WIDTH: usize = 100;

/// Print `text` in lines of at most [`BRIEF_WIDTH`] columns, broken at
/// spaces, each continuation indented by two.
///
/// # Errors
/// As [`line()`].
pub(crate) fn wrapped(text: &str) -> Result<()> {
    use umbra_sim::output::lines::lines;
    let Some((first, rest)) = lines(text, BRIEF_WIDTH).split_first().map(|(f, r)| (f.clone(), r.join(" "))) else {
        return Ok(());
    };
    if !first.is_empty() {
        say!("{first}");
    }
    if !rest.is_empty() {
        for line in lines(&rest, BRIEF_WIDTH - 2) {
            say!("  {line}");
        }
    }
    Ok(())
}

/// Print where a finished folder's files went in `style`: each file and
/// the manifest ([`wrote`]), or one wrapped line naming them.
///
/// # Errors
/// As [`line()`].
pub(crate) fn wrote_in(style: Style, dir: &Path, manifest: &RunManifest, replaced: &Replaced) -> Result<()> {
    match style {
        Style::Full => wrote(dir, manifest, replaced),
        Style::Brief => {
            let names: Vec<&str> = manifest.files.iter().map(|f| f.path.as_str()).chain([MANIFEST]).collect();
            wrapped(&format!("wrote {} files to {}: {}", names.len(), dir.display(), names.join(", ")))?;
            replacements(dir, replaced)
        }
    }
}

/// Print the files a finished folder holds, its manifest last, and what
/// the run replaced there.
///
/// # Errors
/// As [`line()`].
pub(crate) fn wrote(dir: &Path, manifest: &RunManifest, replaced: &Replaced) -> Result<()> {
    for f in &manifest.files {
        say!("wrote {}", dir.join(&f.path).display());
    }
    say!("wrote {}", dir.join(MANIFEST).display());
    replacements(dir, replaced)
}

/// Say what a run replaced in `dir`, on stderr (beside the progress; the
/// results on stdout do not depend on what the folder held before): the
/// earlier run's files it removed or wrote anew, and files no run wrote
/// that it wrote over.
///
/// # Errors
/// None: a closed stderr is not an error of the run.
pub(crate) fn replacements(dir: &Path, replaced: &Replaced) -> Result<()> {
    if let Some(command) = &replaced.command
        && !(replaced.removed.is_empty() && replaced.rewritten.is_empty())
    {
        let removed = if replaced.removed.is_empty() {
            String::new()
        } else {
            format!("; removed {}", replaced.removed.join(", "))
        };
        eprintln!(
            "replaced in {}: {} file(s) of the earlier `{command}`{removed}",
            dir.display(),
            replaced.rewritten.len() + replaced.removed.len()
        );
    }
    if !replaced.overwritten.is_empty() {
        eprintln!(
            "replaced in {} (--replace): {}, which no run of umbra wrote",
            dir.display(),
            replaced.overwritten.join(", ")
        );
    }
    Ok(())
}
