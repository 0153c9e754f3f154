//! What a folder holds and who may write into it: the kind of results a
//! run writes ([`RunKind`]), what it asks of its folder ([`Claim`]), what
//! earlier runs left there, and the rule that admits a run — a new or
//! empty folder, or one of its own kind with nothing else in it, unless
//! the claim replaces what is there — and what the run then replaced
//! ([`Replaced`]).

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{FileRecord, LOCK, MANIFEST, PENDING, Pending, RunManifest, checked_name, problem, read_small};
use crate::output::error::OutputError;

/// The results a folder holds: which command wrote them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum RunKind {
    /// Light-view maps (`umbra depth`).
    Depth,
    /// A render against the reference (`umbra render`).
    Render,
    /// Costs on architectures (`umbra cost`).
    Cost,
    /// A timeline (`umbra trace`).
    Trace,
    /// The model against measured hardware (`umbra correlate`).
    Correlation,
    /// A study, a shard of one, or shards merged (`umbra study`, `umbra merge`).
    Study,
    /// A plan (`umbra plan`).
    Plan,
    /// A generated scene (`umbra scene city`).
    Scene,
}

impl RunKind {
    /// Every kind.
    pub const ALL: [Self; 8] =
        [Self::Depth, Self::Render, Self::Cost, Self::Trace, Self::Correlation, Self::Study, Self::Plan, Self::Scene];

    /// What a folder of this kind holds, as a message names it.
    #[must_use]
    pub const fn describe(self) -> &'static str {
        match self {
            Self::Depth => "light-view maps",
            Self::Render => "a render",
            Self::Cost => "a cost report",
            Self::Trace => "a trace",
            Self::Correlation => "a correlation",
            Self::Study => "a study",
            Self::Plan => "a plan",
            Self::Scene => "a generated scene",
        }
    }

    /// The `umbra` subcommands that write it.
    const fn words(self) -> &'static [&'static str] {
        match self {
            Self::Depth => &["depth"],
            Self::Render => &["render"],
            Self::Cost => &["cost"],
            Self::Trace => &["trace"],
            Self::Correlation => &["correlate"],
            Self::Study => &["study", "merge"],
            Self::Plan => &["plan"],
            Self::Scene => &["scene"],
        }
    }

    /// The kind a command line writes (and a manifest written before
    /// manifests named it holds): the first word of it that is a
    /// subcommand's; `None` for the bare `umbra` (which writes maps, a
    /// render and a study) and commands that write no folder.
    #[must_use]
    pub fn of_command(command: &str) -> Option<Self> {
        command.split_whitespace().skip(1).find_map(|w| Self::ALL.into_iter().find(|k| k.words().contains(&w)))
    }
}

/// What a run asks of its output folder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Claim {
    /// The results it writes.
    pub kind: RunKind,
    /// Replace another command's results, or files no run of Umbra
    /// wrote, deliberately (`--replace`). Files it does not rewrite are
    /// removed only if an earlier run listed them as it wrote them; files
    /// no run wrote, and files this process read, are never removed.
    pub replace: bool,
}

impl Claim {
    /// A run of `kind` that replaces nothing of another's.
    #[must_use]
    pub const fn new(kind: RunKind) -> Self {
        Self { kind, replace: false }
    }

    /// The same, replacing what is there when `replace`.
    #[must_use]
    pub const fn replacing(self, replace: bool) -> Self {
        Self { replace, ..self }
    }
}

/// What a run replaces in its folder: the earlier run's files, and the
/// files no run listed that `--replace` let it write over.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Replaced {
    /// The earlier run's command line, when the folder held a run.
    pub command: Option<String>,
    /// The files the earlier run listed that this one removed (it did not
    /// rewrite them).
    pub removed: Vec<String>,
    /// The files the earlier run listed that this one wrote anew.
    pub rewritten: Vec<String>,
    /// Files no run listed that this one wrote over (only with `--replace`).
    pub overwritten: Vec<String>,
}

/// What earlier runs left in a folder: the files their records list,
/// with their hashes, the results they hold and the command that wrote
/// them, as far as the records are ours; anything else lists nothing (and
/// so is never acted on).
#[derive(Debug, Default)]
pub(super) struct Earlier {
    pub(super) files: Vec<FileRecord>,
    pub(super) kind: Option<RunKind>,
    pub(super) command: Option<String>,
}

impl Earlier {
    /// The records in `dir`: its manifest, then its pending record.
    pub(super) fn read(dir: &Path) -> Self {
        let mut earlier = Self::default();
        if let Ok(m) = read_small(&dir.join(MANIFEST)).and_then(|b| Ok(serde_json::from_slice::<RunManifest>(&b)?)) {
            earlier.kind = m.kind.or_else(|| RunKind::of_command(&m.command));
            earlier.command = Some(m.command);
            earlier.files = m.files;
        }
        if let Ok(p) = read_small(&dir.join(PENDING)).and_then(|b| Ok(serde_json::from_slice::<Pending>(&b)?)) {
            earlier.kind = earlier.kind.or(p.kind);
            earlier.command = earlier.command.or(p.command);
            for f in p.files {
                if !earlier.files.contains(&f) {
                    earlier.files.push(f);
                }
            }
        }
        earlier.files.retain(|f| checked_name(dir, &f.path).is_ok());
        earlier
    }

    /// Whether `name` (`/`-separated, inside the folder) is a file the
    /// records list or a folder one of them lies in.
    fn covers(&self, name: &str) -> bool {
        self.files.iter().any(|f| f.path == name || f.path.strip_prefix(name).is_some_and(|r| r.starts_with('/')))
    }
}

/// The entries of `dir` (its sub-folders too, where the records list a
/// file inside them) that no run of Umbra wrote: not the folder's own
/// records, lock or temporaries, not listed by `earlier`, and not a file
/// this process read. At most `max` entries are looked at.
fn foreign(dir: &Path, earlier: &Earlier, max: usize) -> Vec<String> {
    let mut found = Vec::new();
    let mut stack = vec![String::new()];
    let mut looked = 0usize;
    while let Some(prefix) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(dir.join(&prefix)) else { continue };
        let mut names: Vec<(String, bool)> = entries
            .flatten()
            .map(|e| {
                let name = e.file_name().to_string_lossy().into_owned();
                (name, e.file_type().is_ok_and(|t| t.is_dir()))
            })
            .collect();
        names.sort();
        for (name, is_dir) in names {
            looked += 1;
            if looked > max {
                return found;
            }
            let own = prefix.is_empty() && [MANIFEST, PENDING, LOCK].contains(&name.as_str());
            if own || (name.starts_with(".umbra-") && name.ends_with(".tmp")) {
                continue;
            }
            let path = format!("{prefix}{name}");
            if earlier.files.iter().any(|f| f.path == path) || crate::base::reads::was_read(&dir.join(&path)) {
                continue;
            }
            if is_dir && earlier.covers(&path) {
                stack.push(format!("{path}/"));
            } else {
                found.push(path);
            }
        }
    }
    found
}

/// `names` as a message lists them: the first few, and how many more.
fn list(names: &[String]) -> String {
    const SHOWN: usize = 4;
    let shown: Vec<&str> = names.iter().take(SHOWN).map(String::as_str).collect();
    let more = names.len().saturating_sub(SHOWN);
    if more > 0 { format!("{} and {more} more", shown.join(", ")) } else { shown.join(", ") }
}

/// Whether a run of `claim` may write into `dir`, which holds what
/// `earlier` records: a folder of another command's results, one with
/// files no run of Umbra wrote, and one whose earlier run wrote a file
/// this process read (the run would write it again) are refused,
/// the first two unless the claim replaces them.
pub(super) fn admit(dir: &Path, claim: Claim, earlier: &Earlier) -> Result<(), OutputError> {
    let names: Vec<String> = earlier.files.iter().map(|f| f.path.clone()).collect();
    let by = earlier.command.as_deref().map_or_else(String::new, |c| format!(", written by `{c}`"));
    let inputs: Vec<String> = names.iter().filter(|n| crate::base::reads::was_read(&dir.join(n))).cloned().collect();
    if !inputs.is_empty() && earlier.kind == Some(claim.kind) {
        return Err(problem(
            dir,
            format!(
                "holds {}{by}, whose file {} this run reads and would write again: copy it elsewhere first, or choose another --out",
                claim.kind.describe(),
                list(&inputs)
            ),
        ));
    }
    if claim.replace {
        return Ok(());
    }
    if let Some(kind) = earlier.kind.filter(|&k| k != claim.kind && !names.is_empty()) {
        return Err(problem(
            dir,
            format!(
                "holds {}{by} ({}), not {}: choose another --out, or add --replace to replace it deliberately (files this run reads are kept)",
                kind.describe(),
                list(&names),
                claim.kind.describe()
            ),
        ));
    }
    let foreign = foreign(dir, earlier, 10_000);
    if !foreign.is_empty() {
        return Err(problem(
            dir,
            format!(
                "holds files no run of umbra wrote here ({}): choose another --out (a new or empty folder), or add --replace to write beside them (a file of the same name is replaced; none is deleted)",
                list(&foreign)
            ),
        ));
    }
    Ok(())
}
