//! One rule for a set of shard folders. `status` reports the judgement and
//! `merge` acts on it, so `status` says "ready" exactly when `merge` would
//! write, and names each problem as `merge` refuses it.
//!
//! A set is ready when every folder is a finished study's, named once
//! (however it is reached: by a link, by its `results.jsonl`), of one sweep
//! and one version, split one way, each shard index held once, every shard
//! present, and every row valid and in its shard.

use std::path::{Path, PathBuf};

use serde::Serialize;

use super::{Manifest, beside_rows, invalid, read_manifest, read_rows, refuse, write_run_with};
use crate::experiment::study::{Row, Shard, StudyError, sort_rows};
use crate::input::limits::Limits;
use crate::output::folder::FolderState;
use crate::output::markdown::escape;
use crate::output::table::{Align, Table};

/// A shard folder's state for [`status`].
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShardState {
    /// Finished, every file matching its manifest.
    Complete,
    /// Its run is under way (a pending manifest, the lock held).
    Running,
    /// Its run stopped before finishing (a pending manifest, no lock held).
    Abandoned,
    /// Files differ from its manifest, or the manifest is not a shard's.
    Corrupt,
    /// No run wrote it: nothing there, or not a folder.
    Absent,
}

/// One folder given to [`status`].
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ShardFolder {
    /// The folder, as given.
    pub folder: PathBuf,
    /// What its run left.
    pub state: ShardState,
    /// Its shard, `i/n`, when its manifest says.
    pub shard: Option<String>,
    /// Rows, when complete.
    pub rows: Option<usize>,
    /// Which sweep it is of, or what keeps it out of the merge.
    pub detail: String,
    /// Whether it is fit to merge with the others.
    pub accepted: bool,
}

/// One reason the folders cannot be merged, as `merge` refuses them.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ShardProblem {
    /// The file or folder at fault; `None` for what the set lacks (a
    /// missing shard), which `merge` reports against its output folder.
    pub path: Option<PathBuf>,
    /// What is wrong.
    pub problem: String,
}

/// The state of a sharded run: each folder's, the shards none holds, and
/// every reason a merge would refuse them (Accel-Sim's job status, for a
/// study's shards).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ShardStatus {
    /// Each folder, as given.
    pub folders: Vec<ShardFolder>,
    /// Shards the run was split into, as the first accepted folder says.
    pub count: Option<usize>,
    /// Shard indices no accepted folder holds.
    pub missing: Vec<usize>,
    /// Every reason `merge` would refuse these folders, in the order it
    /// meets them; empty exactly when it would succeed.
    pub problems: Vec<ShardProblem>,
}

/// A folder that passed every check of its own.
struct Accepted {
    /// The folder (not its `results.jsonl`).
    folder: PathBuf,
    manifest: Manifest,
    shard: Shard,
    rows: Vec<Row>,
    /// Its `manifest.json`, named by problems with the set.
    manifest_file: PathBuf,
}

impl ShardStatus {
    /// Every shard present, each once, nothing else given, nothing wrong:
    /// `merge` of these folders would succeed.
    #[must_use]
    pub fn ready(&self) -> bool {
        self.problems.is_empty()
    }

    /// A Markdown table of the folders, a line of what is missing and the
    /// list of problems.
    #[must_use]
    pub fn markdown(&self) -> String {
        use std::fmt::Write as _;
        let mut t = Table::new(&[
            ("folder", Align::Left),
            ("state", Align::Left),
            ("shard", Align::Left),
            ("rows", Align::Right),
            ("detail", Align::Left),
        ]);
        for f in &self.folders {
            let state = serde_json::to_value(&f.state).ok().and_then(|v| v.as_str().map(str::to_owned));
            t.row([
                f.folder.display().to_string(),
                state.unwrap_or_default(),
                f.shard.clone().unwrap_or_else(|| "—".to_owned()),
                f.rows.map_or_else(|| "—".to_owned(), |r| r.to_string()),
                f.detail.clone(),
            ]);
        }
        let mut s = t.markdown();
        let done = self.folders.iter().filter(|f| f.accepted).count();
        match self.count {
            Some(n) if self.ready() => {
                let _ = writeln!(s, "\n{done} of {n} shards complete: ready to merge.");
            }
            Some(n) if !self.missing.is_empty() => {
                let list: Vec<String> = self.missing.iter().map(|i| format!("{i}/{n}")).collect();
                let _ = writeln!(
                    s,
                    "\n{} of {n} shards complete; not complete: {} (rerun each, e.g. `sbatch --array={}`).",
                    n - self.missing.len(),
                    list.join(", "),
                    self.missing.iter().map(usize::to_string).collect::<Vec<_>>().join(",")
                );
            }
            Some(n) => {
                let _ = writeln!(s, "\n{done} of {n} shards complete.");
            }
            None => {
                let _ = writeln!(s, "\nNo complete shard: the count of shards is not known yet.");
            }
        }
        if !self.ready() {
            let _ = writeln!(s, "\nNot ready to merge ({} problem(s)):\n", self.problems.len());
            for p in &self.problems {
                let at = p.path.as_ref().map_or_else(String::new, |p| format!("`{}`: ", p.display()));
                let _ = writeln!(s, "- {}{}", escape(&at), escape(&p.problem));
            }
        }
        s
    }
}

/// The folder a shard input names: the folder itself, or the folder of
/// its `results.jsonl`.
fn shard_folder(input: &Path) -> Result<PathBuf, String> {
    if input.is_dir() {
        return Ok(input.to_owned());
    }
    if input.is_file() {
        return match (input.file_name(), input.parent()) {
            (Some(name), Some(parent)) if name == "results.jsonl" => {
                Ok(if parent.as_os_str().is_empty() { PathBuf::from(".") } else { parent.to_owned() })
            }
            _ => Err("is a file, not a study's folder: give the folder a study wrote, or its results.jsonl".into()),
        };
    }
    if input.exists() {
        return Err("is not a regular file or a folder: give the folder a study wrote, or its results.jsonl".into());
    }
    if std::fs::symlink_metadata(input).is_ok() {
        return Err("is a symbolic link to nothing: give the folder a study wrote".into());
    }
    Err("does not exist: no run wrote it".into())
}

/// Judge one input on its own: its state, and its shard when it passes
/// every check that needs no other folder.
fn examine(input: &Path, limits: &Limits) -> (ShardFolder, Result<Accepted, ShardProblem>) {
    let folder = |state, detail: String| ShardFolder {
        folder: input.to_owned(),
        state,
        shard: None,
        rows: None,
        detail,
        accepted: false,
    };
    let problem = |path: &Path, problem: String| ShardProblem { path: Some(path.to_owned()), problem };
    let dir = match shard_folder(input) {
        Ok(dir) => dir,
        Err(why) => return (folder(ShardState::Absent, why.clone()), Err(problem(input, why))),
    };
    let unfinished = |state, why: &str| {
        let text =
            format!("is not a finished shard: {why}; `umbra status` lists every shard's state, then rerun this one");
        (folder(state, why.to_owned()), Err(problem(&dir, text)))
    };
    match FolderState::of(&dir, limits.max_file_bytes) {
        FolderState::Complete(_) => {}
        FolderState::Running => return unfinished(ShardState::Running, "its run is under way (its lock is held)"),
        FolderState::Abandoned => {
            return unfinished(ShardState::Abandoned, "its run stopped before finishing (killed or lost)");
        }
        FolderState::Corrupt(e) => return (folder(ShardState::Corrupt, e.clone()), Err(problem(&dir, e))),
        FolderState::Absent => {
            let why = "no run wrote it: it holds no manifest.json".to_owned();
            return (folder(ShardState::Absent, why.clone()), Err(problem(&dir.join("manifest.json"), why)));
        }
    }
    let as_problem = |e: StudyError| match e {
        StudyError::Merge { path, problem } => ShardProblem { path: Some(path), problem },
        e => ShardProblem { path: Some(dir.clone()), problem: e.to_string() },
    };
    let (manifest_file, m) = match read_manifest(&dir, limits) {
        Ok(read) => read,
        Err(e) => {
            let p = as_problem(e);
            return (folder(ShardState::Corrupt, p.problem.clone()), Err(p));
        }
    };
    let mut shown = folder(ShardState::Complete, format!("sweep {} {}", m.sweep, m.sweep_hash));
    shown.shard = Some(m.shard.clone());
    shown.rows = Some(m.rows);
    let checked = own_checks(&dir, &manifest_file, &m, limits).map_err(as_problem);
    match checked {
        Ok((shard, rows)) => {
            shown.accepted = true;
            (shown, Ok(Accepted { folder: dir, manifest: m, shard, rows, manifest_file }))
        }
        Err(p) => {
            shown.detail.clone_from(&p.problem);
            (shown, Err(p))
        }
    }
}

/// The checks of a finished study folder that need no other folder: its
/// shard reads as `i/n`, its budgets and layout are a sweep's, its rows
/// are the count its manifest says, each valid and in its shard.
fn own_checks(dir: &Path, file: &Path, m: &Manifest, limits: &Limits) -> Result<(Shard, Vec<Row>), StudyError> {
    let shard = Shard::parse(&m.shard).map_err(|_| refuse(file, format!("shard `{}` is not i/n", m.shard)))?;
    if let Some((i, problem)) = crate::experiment::study::budgets_problem(&m.budgets) {
        return Err(refuse(file, format!("budgets[{i}]: {problem}")));
    }
    if m.layout.configurations != m.configurations {
        return Err(refuse(file, "its layout of configurations is not the sweep's"));
    }
    let rows_file = dir.join("results.jsonl");
    let rows = read_rows(&rows_file, limits)?;
    if rows.len() != m.rows {
        return Err(refuse(&rows_file, format!("{} rows where the manifest says {}", rows.len(), m.rows)));
    }
    for r in &rows {
        let at = format!("row {} ({})", r.config_index, r.config.arch);
        if !shard.contains(&m.layout, r.config_index) {
            return Err(refuse(&rows_file, format!("{at} is not in shard {}", m.shard)));
        }
        if r.config.sweep_hash != m.sweep_hash {
            return Err(refuse(&rows_file, format!("{at} is of sweep {}, not {}", r.config.sweep_hash, m.sweep_hash)));
        }
        if let Some(problem) = invalid(r) {
            return Err(refuse(&rows_file, format!("{at}: {problem}")));
        }
    }
    Ok((shard, rows))
}

/// Why `b` cannot be merged with `first` (the first folder accepted), if
/// it cannot.
fn against_first(first: &Accepted, b: &Accepted) -> Option<String> {
    let (f, m) = (&first.manifest, &b.manifest);
    if (f.sweep_hash.as_str(), f.umbra_version.as_str()) != (m.sweep_hash.as_str(), m.umbra_version.as_str()) {
        return Some(format!(
            "a shard of another sweep or version ({} {}, not {} {} as in `{}`)",
            m.sweep_hash,
            m.umbra_version,
            f.sweep_hash,
            f.umbra_version,
            first.folder.display()
        ));
    }
    if first.shard.count != b.shard.count {
        let unsharded = |s: Shard| s.count == 1;
        return Some(if unsharded(first.shard) || unsharded(b.shard) {
            format!(
                "shard {} beside shard {} of `{}`: a whole run (n = 1) and shards are never merged together",
                m.shard,
                f.shard,
                first.folder.display()
            )
        } else {
            format!("shard {} of a run split {}-ways, not like {}", m.shard, b.shard.count, f.shard)
        });
    }
    if m.layout != f.layout {
        return Some("its layout of configurations is not the sweep's".to_owned());
    }
    None
}

/// Judge `inputs` as the shards of one run: the status `status` prints and
/// the folders `merge` would merge (in the order given), ready exactly when
/// `status.problems` is empty.
fn judge(inputs: &[PathBuf], limits: &Limits) -> (ShardStatus, Vec<Accepted>) {
    let mut folders: Vec<ShardFolder> = Vec::new();
    let mut problems = Vec::new();
    let mut accepted: Vec<Accepted> = Vec::new();
    // Each folder once however it is named (a link, a relative path, its
    // results file): its resolved path and where it was first given.
    let mut seen: Vec<(PathBuf, usize)> = Vec::new();
    for input in inputs {
        let canonical = shard_folder(input).ok().and_then(|d| d.canonicalize().ok());
        if let Some((_, earlier)) = seen.iter().find(|(s, _)| Some(s) == canonical.as_ref()) {
            let first = &folders[*earlier];
            let why =
                format!("is the folder `{}` given again (the same folder, however named)", first.folder.display());
            let again = ShardFolder { folder: input.clone(), detail: why.clone(), accepted: false, ..first.clone() };
            folders.push(again);
            problems.push(ShardProblem { path: Some(input.clone()), problem: why });
            continue;
        }
        if let Some(c) = canonical {
            seen.push((c, folders.len()));
        }
        let (mut shown, judged) = examine(input, limits);
        match judged {
            Ok(a) => {
                let clash = accepted.first().and_then(|first| against_first(first, &a)).or_else(|| {
                    let earlier = accepted.iter().find(|e| e.shard.index == a.shard.index)?;
                    Some(format!("shard {} is given twice (also `{}`)", a.manifest.shard, earlier.folder.display()))
                });
                if let Some(why) = clash {
                    shown.accepted = false;
                    shown.detail.clone_from(&why);
                    problems.push(ShardProblem { path: Some(a.manifest_file.clone()), problem: why });
                } else {
                    accepted.push(a);
                }
            }
            Err(p) => problems.push(p),
        }
        folders.push(shown);
    }
    let count = accepted.first().map(|a| a.shard.count);
    let missing: Vec<usize> =
        count.map_or_else(Vec::new, |n| (0..n).filter(|i| !accepted.iter().any(|a| a.shard.index == *i)).collect());
    match (accepted.first(), count) {
        (Some(first), Some(n)) if !missing.is_empty() => {
            let list: Vec<String> = missing.iter().map(|i| format!("{i}/{n}")).collect();
            let (noun, verb) = if missing.len() == 1 { ("shard", "is") } else { ("shards", "are") };
            problems.push(ShardProblem {
                path: None,
                problem: format!("{noun} {} of sweep {} {verb} missing", list.join(", "), first.manifest.sweep_hash),
            });
        }
        (None, _) if problems.is_empty() => {
            problems.push(ShardProblem { path: None, problem: "no shard to merge".into() });
        }
        _ => {}
    }
    if problems.is_empty() {
        problems.extend(whole_set_problem(&accepted));
    }
    (ShardStatus { folders, count, missing, problems }, accepted)
}

/// What only the whole set shows: a row held twice, and rows that do not
/// add up to the sweep's.
fn whole_set_problem(accepted: &[Accepted]) -> Option<ShardProblem> {
    let first = accepted.first()?;
    let mut keys: Vec<(usize, usize, &str)> = accepted
        .iter()
        .flat_map(|a| a.rows.iter().map(|r| (r.config_index, r.arch_index, r.config.arch.as_str())))
        .collect();
    keys.sort_unstable();
    if let Some(w) = keys.windows(2).find(|w| (w[0].0, w[0].1) == (w[1].0, w[1].1)) {
        return Some(ShardProblem {
            path: None,
            problem: format!("row {} ({}) appears twice among the merged files (overlapping shards?)", w[0].0, w[0].2),
        });
    }
    let m = &first.manifest;
    let expected = m.configurations.checked_mul(m.architectures);
    (expected != Some(keys.len())).then(|| {
        let expected = expected.map_or_else(|| "more than can be counted".to_owned(), |n| n.to_string());
        ShardProblem { path: None, problem: format!("{} rows merged where the sweep has {expected}", keys.len()) }
    })
}

/// The state of each shard folder in `inputs`, the shards none of the
/// accepted ones holds, and every reason [`merge`] would refuse them.
#[must_use]
pub fn status(inputs: &[PathBuf], limits: &Limits) -> ShardStatus {
    judge(inputs, limits).0
}

/// Read shard outputs (folders, or their `results.jsonl`), each with the
/// `manifest.json` its run wrote, and write the whole run's files into
/// `out`. Returns the number of rows.
///
/// Refused exactly when [`status`] of `inputs` is not ready, with its first
/// problem (the file named, or `out` for what the set lacks); `out` may not
/// be one of the inputs.
///
/// # Errors
/// See [`StudyError`].
pub fn merge(inputs: &[PathBuf], out: &Path, limits: &Limits) -> Result<usize, StudyError> {
    merge_replacing(inputs, (out, false), limits)
}

/// [`merge`] into `out`, replacing another command's results there, or
/// files no run of Umbra wrote, when `replace` (`--replace`).
///
/// # Errors
/// See [`StudyError`].
pub fn merge_replacing(
    inputs: &[PathBuf],
    (out, replace): (&Path, bool),
    limits: &Limits,
) -> Result<usize, StudyError> {
    // The output is written while the inputs are read: never one of them.
    let same = |a: &Path, b: &Path| a.canonicalize().ok().zip(b.canonicalize().ok()).is_some_and(|(a, b)| a == b);
    if let Some(input) = inputs.iter().find(|i| same(i, out) || same(&shard_folder(i).unwrap_or_default(), out)) {
        return Err(refuse(input, "is also --out: merge writes a new folder and never replaces a shard".to_owned()));
    }
    let (status, accepted) = judge(inputs, limits);
    if let Some(p) = status.problems.first() {
        let more = match status.problems.len() - 1 {
            0 => String::new(),
            n => format!(" (and {n} more: `umbra status` lists them all)"),
        };
        return Err(refuse(p.path.as_deref().unwrap_or(out), format!("{}{more}", p.problem)));
    }
    let Some(first) = accepted.first() else { return Err(refuse(out, "no shard to merge")) };
    let m = first.manifest.clone();
    let beside = beside_rows(&first.folder, limits)?;
    let mut rows: Vec<Row> = accepted.into_iter().flat_map(|a| a.rows).collect();
    sort_rows(&mut rows);
    let whole =
        Manifest { shard: "0/1".into(), rows: rows.len(), command: crate::output::provenance::command_line(), ..m };
    write_run_with((out, replace), &rows, &whole, &beside)?;
    Ok(rows.len())
}
