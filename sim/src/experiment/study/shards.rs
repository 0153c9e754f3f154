//! Rows written as JSON lines with a manifest, read back, and shards merged
//! into one run — refusing anything that would make the merge lie.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{Layout, Row, Shard, Spec, Status, StudyError, sort_rows, write_outputs};
use crate::input::limits::Limits;
use crate::output::folder::{OutputFolder, RunManifest};

/// What a study run (whole or one shard) wrote: enough to tell whether
/// shards belong together and are complete.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The sweep's name.
    pub sweep: String,
    /// The sweep file's hash.
    pub sweep_hash: String,
    /// The version that ran it.
    pub umbra_version: String,
    /// This shard, `i/n` (`0/1` for a whole run).
    pub shard: String,
    /// Configurations in the whole sweep.
    pub configurations: usize,
    /// How they fall into the blocks shards keep whole.
    pub layout: Layout,
    /// Architectures each configuration is costed on (1 when none).
    pub architectures: usize,
    /// Rows in this run's `results.jsonl`.
    pub rows: usize,
    /// The summary's error budgets, percent artifacts.
    pub budgets: Vec<f64>,
    /// The command line that made it.
    pub command: String,
}

impl Manifest {
    /// The manifest of `rows`, the run of `shard` of `spec`.
    #[must_use]
    pub(crate) fn new(spec: &Spec, shard: Shard, rows: usize) -> Self {
        Self {
            sweep: spec.name.clone(),
            sweep_hash: spec.hash.clone(),
            umbra_version: crate::output::provenance::version(),
            shard: format!("{}/{}", shard.index, shard.count),
            configurations: spec.configs().len(),
            layout: Layout::of(spec),
            architectures: spec.archs.len().max(1),
            rows,
            budgets: spec.budgets.clone(),
            command: crate::output::provenance::command_line(),
        }
    }
}

/// The rows as JSON lines.
pub(super) fn jsonl(rows: &[Row]) -> String {
    let mut s = String::new();
    for r in rows {
        // A Row holds only strings, numbers, booleans and options: it always serialises.
        s.push_str(&serde_json::to_string(r).unwrap_or_default());
        s.push('\n');
    }
    s
}

/// Write a shard's partial `results.jsonl` into `folder`.
///
/// # Errors
/// [`StudyError::Output`].
pub fn write_partial(folder: &mut OutputFolder, rows: &[Row]) -> Result<(), StudyError> {
    folder.write_text("results.jsonl", &jsonl(rows))?;
    Ok(())
}

/// Finish a study's folder: its `manifest.json` lists the files and
/// carries `manifest` as its `study` record.
///
/// # Errors
/// [`StudyError::Output`].
pub fn finish(folder: OutputFolder, manifest: &Manifest) -> Result<RunManifest, StudyError> {
    // A Manifest holds only strings and numbers: it always serialises.
    Ok(folder.finish(serde_json::to_value(manifest).ok())?)
}

#[cfg(test)]
/// Write a whole run's files (or, for a shard, its rows) into a fresh
/// folder `dir` and finish it.
///
/// # Errors
/// See [`StudyError`].
pub(crate) fn write_run(dir: &Path, rows: &[Row], manifest: &Manifest) -> Result<RunManifest, StudyError> {
    write_run_with(dir, rows, manifest, &[])
}

/// Write a whole run's files (or, for a shard, its rows) into a fresh
/// folder `dir`, then `extra` files (name, bytes) after the outputs, and
/// finish it.
fn write_run_with(
    dir: &Path,
    rows: &[Row],
    manifest: &Manifest,
    extra: &[(String, Vec<u8>)],
) -> Result<RunManifest, StudyError> {
    let mut folder = OutputFolder::create(dir)?;
    if manifest.shard == "0/1" {
        write_outputs(&mut folder, rows, manifest)?;
    } else {
        write_partial(&mut folder, rows)?;
    }
    for (name, bytes) in extra {
        folder.write(name, bytes)?;
    }
    finish(folder, manifest)
}

/// The files a study's command writes beside its rows — the sweep file and
/// the effective architectures, the same in every shard of a sweep — read
/// from a verified shard folder in the order its manifest lists them.
fn beside_rows(dir: &Path, limits: &Limits) -> Result<Vec<(String, Vec<u8>)>, StudyError> {
    let run = RunManifest::verify(dir, limits.max_file_bytes)?;
    run.files
        .iter()
        .filter(|f| f.path == "sweep.toml" || (f.path.starts_with("arch-") && f.path.ends_with(".toml")))
        .map(|f| {
            let path = dir.join(&f.path);
            let bytes = limits.read_file(&path).map_err(|source| StudyError::Read { path, source })?;
            Ok((f.path.clone(), bytes))
        })
        .collect()
}

/// Read the rows of a `results.jsonl` (or of the one in a folder), a file
/// of at most [`Limits::max_file_bytes`].
///
/// # Errors
/// [`StudyError::Read`] or [`StudyError::Parse`] naming the file and line
/// (a line that is not UTF-8 is not a row).
pub fn read_rows(path: &Path, limits: &Limits) -> Result<Vec<Row>, StudyError> {
    let file = if path.is_dir() { path.join("results.jsonl") } else { path.to_owned() };
    let bytes = limits.read_file(&file).map_err(|source| StudyError::Read { path: file.clone(), source })?;
    // Line by line as bytes: a line that is not UTF-8 is refused by the
    // parser, never read with a replacement character as another scene.
    bytes
        .split(|&b| b == b'\n')
        .enumerate()
        .filter(|(_, l)| !l.trim_ascii().is_empty())
        .map(|(i, l)| {
            serde_json::from_slice(l).map_err(|source| StudyError::Parse { path: file.clone(), line: i + 1, source })
        })
        .collect()
}

/// Read the `manifest.json` beside a shard's rows, having checked every
/// file it lists (a truncated or changed results file does not match).
fn read_manifest(input: &Path, limits: &Limits) -> Result<(PathBuf, Manifest), StudyError> {
    let dir = if input.is_dir() { input.to_owned() } else { input.parent().unwrap_or(Path::new(".")).to_owned() };
    let file = dir.join(crate::output::folder::MANIFEST);
    let run = RunManifest::verify(&dir, limits.max_file_bytes)?;
    if !run.files.iter().any(|f| f.path == "results.jsonl") {
        return Err(refuse(&file, "lists no results.jsonl: not a study's folder"));
    }
    let study = run.study.ok_or_else(|| refuse(&file, "has no study record: not a study's folder"))?;
    let m =
        serde_json::from_value(study).map_err(|source| StudyError::Parse { path: file.clone(), line: 0, source })?;
    Ok((file, m))
}

fn refuse(path: &Path, problem: impl Into<String>) -> StudyError {
    StudyError::Merge { path: path.to_owned(), problem: problem.into() }
}

/// Why `r` is not a row a study writes, if it is not: a known status with
/// the blocks it implies, finite numbers, values in their ranges.
#[must_use]
pub(crate) fn invalid(r: &Row) -> Option<String> {
    match (r.status, &r.metrics) {
        (Status::Ok, None) => return Some("status ok without metrics".into()),
        (Status::Skipped, _) if r.reason.is_empty() => return Some("skipped without a reason".into()),
        (Status::Skipped, Some(_)) => return Some("skipped with metrics".into()),
        _ => {}
    }
    if let Some(m) = &r.metrics {
        for (name, v, hi) in [
            ("misclassified_percent", m.misclassified_percent, 100.0),
            ("artifact_percent", m.artifact_percent, 100.0),
            ("mean_abs_error", m.mean_abs_error, 1.0),
            ("rms_error", m.rms_error, 1.0),
            ("virtual_sample_percent", m.virtual_sample_percent, 100.0),
        ] {
            if !(v.is_finite() && (0.0..=hi).contains(&v)) {
                return Some(format!("{name} {v} is outside 0…{hi}"));
            }
        }
        for (name, v) in [
            ("displacement_mean_px", m.displacement_mean_px),
            ("displacement_p95_px", m.displacement_p95_px),
            ("aliasing_area_px", m.aliasing_area_px),
            ("penumbra_area_px", m.penumbra_area_px),
            ("acne_area_px", m.acne_area_px),
            ("detachment_area_px", m.detachment_area_px),
            ("leak_area_px", m.leak_area_px),
            ("penumbra_width_p95_px", m.penumbra_width_p95_px),
            ("footprint_x_texels_per_px", m.footprint_x_texels_per_px),
            ("footprint_y_texels_per_px", m.footprint_y_texels_per_px),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Some(format!("{name} {v} is not a finite non-negative number"));
            }
        }
        if m.false_shadow_px.checked_add(m.false_light_px).is_none_or(|n| n > m.evaluated_px) {
            return Some("more misclassified pixels than evaluated".into());
        }
        let classes = [m.aliasing_px, m.penumbra_px, m.acne_px, m.detachment_px, m.leaks_px];
        let wrong = classes.iter().try_fold(0u64, |a, &n| a.checked_add(n));
        if wrong.is_none_or(|n| n > m.evaluated_px) {
            return Some("more wrong pixels (aliasing, penumbra, acne, detachment, leaks) than evaluated".into());
        }
        if m.terminator_acne_px > m.acne_px {
            return Some("more terminator acne than acne".into());
        }
    }
    if let Some(c) = &r.cost {
        for (name, v) in [
            ("frame_seconds", c.frame_seconds),
            ("frames_per_second", c.frames_per_second),
            ("energy_joules", c.energy_joules),
            ("dram_achieved_bytes_per_second", c.dram_achieved_bytes_per_second),
            ("map_bytes_per_px", c.map_bytes_per_px),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Some(format!("{name} {v} is not a finite non-negative number"));
            }
        }
        if c.total_cycles == 0 {
            return Some("a costed frame of 0 cycles".into());
        }
    }
    None
}

/// Read shard outputs (folders, or their `results.jsonl`), each with the
/// `manifest.json` its run wrote, and write the whole run's files into
/// `out`. Returns the number of rows.
///
/// Refused, each with the file named: a shard without a manifest, of
/// another sweep or version, of another shard count, twice; a missing
/// shard; a row count that is not the manifest's; a row outside its shard,
/// of another sweep, repeated, or failing `invalid`.
///
/// # Errors
/// See [`StudyError`].
pub fn merge(inputs: &[PathBuf], out: &Path, limits: &Limits) -> Result<usize, StudyError> {
    // The output is written while the inputs are read: never one of them.
    let same = |a: &Path, b: &Path| a.canonicalize().ok().zip(b.canonicalize().ok()).is_some_and(|(a, b)| a == b);
    if let Some(input) = inputs.iter().find(|i| same(i, out)) {
        return Err(refuse(input, "is also --out: merge writes a new folder and never replaces a shard".to_owned()));
    }
    let mut rows = Vec::new();
    let mut first: Option<Manifest> = None;
    let mut seen: Vec<usize> = Vec::new();
    for input in inputs {
        use crate::output::folder::FolderState;
        if input.is_dir() {
            let unfinished = match FolderState::unfinished(input) {
                Some(FolderState::Running) => Some("its run is under way"),
                Some(FolderState::Abandoned) => Some("its run stopped before finishing (killed or lost)"),
                _ => None,
            };
            if let Some(why) = unfinished {
                return Err(refuse(
                    input,
                    format!(
                        "is not a finished shard: {why}; `umbra status` lists every shard's state, then rerun this one"
                    ),
                ));
            }
        }
        let mine = read_rows(input, limits)?;
        let (file, m) = read_manifest(input, limits)?;
        let shard = Shard::parse(&m.shard).map_err(|_| refuse(&file, format!("shard `{}` is not i/n", m.shard)))?;
        if let Some((i, problem)) = super::budgets_problem(&m.budgets) {
            return Err(refuse(&file, format!("budgets[{i}]: {problem}")));
        }
        if let Some(f) = &first {
            if (f.sweep_hash.as_str(), f.umbra_version.as_str()) != (m.sweep_hash.as_str(), m.umbra_version.as_str()) {
                return Err(refuse(
                    &file,
                    format!(
                        "a shard of another sweep or version ({} {}, not {} {})",
                        m.sweep_hash, m.umbra_version, f.sweep_hash, f.umbra_version
                    ),
                ));
            }
            if Shard::parse(&f.shard).map(|s| s.count).ok() != Some(shard.count) {
                return Err(refuse(
                    &file,
                    format!("shard {} of a run split {}-ways, not like {}", m.shard, shard.count, f.shard),
                ));
            }
        }
        if m.layout.configurations != m.configurations || first.as_ref().is_some_and(|f| f.layout != m.layout) {
            return Err(refuse(&file, "its layout of configurations is not the sweep's".to_owned()));
        }
        if seen.contains(&shard.index) {
            return Err(refuse(&file, format!("shard {} is given twice", m.shard)));
        }
        seen.push(shard.index);
        let rows_file = if input.is_dir() { input.join("results.jsonl") } else { input.clone() };
        if mine.len() != m.rows {
            return Err(refuse(&rows_file, format!("{} rows where the manifest says {}", mine.len(), m.rows)));
        }
        for r in &mine {
            let at = format!("row {} ({})", r.config_index, r.config.arch);
            if !shard.contains(&m.layout, r.config_index) {
                return Err(refuse(&rows_file, format!("{at} is not in shard {}", m.shard)));
            }
            if r.config.sweep_hash != m.sweep_hash {
                return Err(refuse(
                    &rows_file,
                    format!("{at} is of sweep {}, not {}", r.config.sweep_hash, m.sweep_hash),
                ));
            }
            if let Some(problem) = invalid(r) {
                return Err(refuse(&rows_file, format!("{at}: {problem}")));
            }
        }
        rows.extend(mine);
        first.get_or_insert(m);
    }
    let Some(m) = first else { return Err(refuse(out, "no shard to merge")) };
    let count = Shard::parse(&m.shard).map_or(1, |s| s.count);
    if let Some(missing) = (0..count).find(|i| !seen.contains(i)) {
        return Err(refuse(out, format!("shard {missing}/{count} of sweep {} is missing", m.sweep_hash)));
    }
    sort_rows(&mut rows);
    if let Some(w) =
        rows.windows(2).find(|w| (w[0].config_index, w[0].arch_index) == (w[1].config_index, w[1].arch_index))
    {
        return Err(StudyError::Duplicate { index: w[0].config_index, arch: w[0].config.arch.clone() });
    }
    let expected = m.configurations.checked_mul(m.architectures);
    if expected != Some(rows.len()) {
        let expected = expected.map_or_else(|| "more than can be counted".to_owned(), |n| n.to_string());
        return Err(refuse(out, format!("{} rows merged where the sweep has {expected}", rows.len())));
    }
    let whole =
        Manifest { shard: "0/1".into(), rows: rows.len(), command: crate::output::provenance::command_line(), ..m };
    // The sweep file and architectures the shards' command wrote, as the
    // unsharded run writes them.
    let extra = match inputs.iter().find(|i| i.is_dir()) {
        Some(dir) => beside_rows(dir, limits)?,
        None => Vec::new(),
    };
    write_run_with(out, &rows, &whole, &extra)?;
    Ok(rows.len())
}

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
    /// No run wrote it.
    Absent,
}

/// One folder given to [`status`].
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ShardFolder {
    /// The folder.
    pub folder: PathBuf,
    /// What its run left.
    pub state: ShardState,
    /// Its shard, `i/n`, when its manifest says.
    pub shard: Option<String>,
    /// Rows, when complete.
    pub rows: Option<usize>,
    /// What is wrong, or which sweep it is of.
    pub detail: String,
}

/// The state of a sharded run: each folder's, and the shards no complete
/// folder holds (Accel-Sim's job status, for a study's shards).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ShardStatus {
    /// Each folder, as given.
    pub folders: Vec<ShardFolder>,
    /// Shards the run was split into, as the complete ones say.
    pub count: Option<usize>,
    /// Shard indices no complete folder holds.
    pub missing: Vec<usize>,
}

impl ShardStatus {
    /// Every shard complete, and nothing else given.
    #[must_use]
    pub fn complete(&self) -> bool {
        self.count.is_some() && self.missing.is_empty() && self.folders.iter().all(|f| f.state == ShardState::Complete)
    }

    /// A Markdown table of the folders and a line of what is missing.
    #[must_use]
    pub fn markdown(&self) -> String {
        use std::fmt::Write as _;
        let mut s = String::from("| folder | state | shard | rows | detail |\n|---|---|---|---:|---|\n");
        for f in &self.folders {
            let state = serde_json::to_value(&f.state).ok().and_then(|v| v.as_str().map(str::to_owned));
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} |",
                f.folder.display(),
                state.unwrap_or_default(),
                f.shard.as_deref().unwrap_or("—"),
                f.rows.map_or_else(|| "—".to_owned(), |r| r.to_string()),
                f.detail.replace('|', "\\|")
            );
        }
        let done = self.folders.iter().filter(|f| f.state == ShardState::Complete).count();
        match self.count {
            Some(n) if self.missing.is_empty() => {
                let _ = writeln!(s, "\n{done} of {n} shards complete: ready to merge.");
            }
            Some(n) => {
                let list: Vec<String> = self.missing.iter().map(|i| format!("{i}/{n}")).collect();
                let _ = writeln!(
                    s,
                    "\n{} of {n} shards complete; not complete: {} (rerun each, e.g. `sbatch --array={}`).",
                    n - self.missing.len(),
                    list.join(", "),
                    self.missing.iter().map(usize::to_string).collect::<Vec<_>>().join(",")
                );
            }
            None => {
                let _ = writeln!(s, "\nNo complete shard: the count of shards is not known yet.");
            }
        }
        s
    }
}

/// The state of each shard folder in `inputs`, and the shards none of the
/// complete ones holds.
#[must_use]
pub fn status(inputs: &[PathBuf], limits: &Limits) -> ShardStatus {
    use crate::output::folder::FolderState;
    let mut folders = Vec::new();
    let mut held: Vec<usize> = Vec::new();
    let mut count: Option<usize> = None;
    for input in inputs {
        let (state, shard, rows, detail) = match FolderState::of(input, limits.max_file_bytes) {
            FolderState::Complete(_) => match read_manifest(input, limits) {
                Ok((_, m)) => match Shard::parse(&m.shard) {
                    Ok(s) => {
                        held.push(s.index);
                        count.get_or_insert(s.count);
                        let detail = format!("sweep {} {}", m.sweep, m.sweep_hash);
                        (ShardState::Complete, Some(m.shard), Some(m.rows), detail)
                    }
                    Err(_) => (ShardState::Corrupt, None, None, format!("shard `{}` is not i/n", m.shard)),
                },
                Err(e) => (ShardState::Corrupt, None, None, e.to_string()),
            },
            FolderState::Running => (ShardState::Running, None, None, "under way (its lock is held)".into()),
            FolderState::Abandoned => {
                (ShardState::Abandoned, None, None, "stopped before finishing (a pending manifest, no lock)".into())
            }
            FolderState::Corrupt(e) => (ShardState::Corrupt, None, None, e),
            FolderState::Absent => (ShardState::Absent, None, None, "no run wrote it".into()),
        };
        folders.push(ShardFolder { folder: input.clone(), state, shard, rows, detail });
    }
    let missing = count.map_or_else(Vec::new, |n| (0..n).filter(|i| !held.contains(i)).collect());
    ShardStatus { folders, count, missing }
}

/// A shard folder `dir` that already holds `manifest`'s shard, complete
/// and verified, of the same sweep and version: running it again would
/// write the same bytes.
#[must_use]
pub fn already_complete(dir: &Path, manifest: &Manifest, limits: &Limits) -> bool {
    read_manifest(dir, limits).is_ok_and(|(_, m)| {
        (m.sweep_hash.as_str(), m.umbra_version.as_str(), m.shard.as_str(), m.configurations, m.architectures)
            == (
                manifest.sweep_hash.as_str(),
                manifest.umbra_version.as_str(),
                manifest.shard.as_str(),
                manifest.configurations,
                manifest.architectures,
            )
    })
}
