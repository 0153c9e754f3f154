//! Rows written as JSON lines with a manifest, read back, and shards merged
//! into one run — refusing anything that would make the merge lie.

mod judge;

pub use judge::{ShardFolder, ShardProblem, ShardState, ShardStatus, merge, merge_replacing, status};

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{Layout, Row, Shard, Spec, Status, StudyError, write_outputs};
use crate::input::limits::Limits;
use crate::output::folder::{Claim, OutputFolder, Replaced, RunKind, RunManifest};

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
    /// The summary's error budgets: numbers for artifacts (as earlier
    /// manifests wrote them), `MEASURE=PERCENT` for another measure.
    #[serde(with = "crate::experiment::study::budget::written")]
    pub budgets: Vec<crate::experiment::study::budget::Budget>,
    /// The most the summary's best per objective may cost (none in an
    /// earlier release's manifest).
    #[serde(default)]
    pub cost_limits: super::objective::CostLimits,
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
            cost_limits: spec.cost_limits,
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
pub fn finish(folder: OutputFolder, manifest: &Manifest) -> Result<(RunManifest, Replaced), StudyError> {
    // A Manifest holds only strings and numbers: it always serialises.
    Ok(folder.finish_replacing(serde_json::to_value(manifest).ok())?)
}

#[cfg(test)]
/// Write a whole run's files (or, for a shard, its rows) into a fresh
/// folder `dir` and finish it.
///
/// # Errors
/// See [`StudyError`].
pub(crate) fn write_run(dir: &Path, rows: &[Row], manifest: &Manifest) -> Result<RunManifest, StudyError> {
    write_run_with((dir, false), rows, manifest, &[])
}

/// Write a whole run's files (or, for a shard, its rows) into a fresh
/// folder `dir`, then `extra` files (name, bytes) after the outputs, and
/// finish it.
fn write_run_with(
    (dir, replace): (&Path, bool),
    rows: &[Row],
    manifest: &Manifest,
    extra: &[(String, Vec<u8>)],
) -> Result<RunManifest, StudyError> {
    let mut folder = OutputFolder::create(dir, Claim::new(RunKind::Study).replacing(replace))?;
    if manifest.shard == "0/1" {
        write_outputs(&mut folder, rows, manifest)?;
    } else {
        write_partial(&mut folder, rows)?;
    }
    for (name, bytes) in extra {
        folder.write(name, bytes)?;
    }
    finish(folder, manifest).map(|(m, _)| m)
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
            let bytes = limits.read_output(&path).map_err(|source| StudyError::Read { path, source })?;
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
    let bytes = limits.read_output(&file).map_err(|source| StudyError::Read { path: file.clone(), source })?;
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
/// (The folder's own record and its study record name one version: a
/// record edited to pass as another version's is refused.)
fn read_manifest(input: &Path, limits: &Limits) -> Result<(PathBuf, Manifest), StudyError> {
    let dir = if input.is_dir() { input.to_owned() } else { input.parent().unwrap_or(Path::new(".")).to_owned() };
    let file = dir.join(crate::output::folder::MANIFEST);
    let run = RunManifest::verify(&dir, limits.max_file_bytes)?;
    if !run.files.iter().any(|f| f.path == "results.jsonl") {
        return Err(refuse(&file, "lists no results.jsonl: not a study's folder"));
    }
    let study = run.study.ok_or_else(|| refuse(&file, "has no study record: not a study's folder"))?;
    let m: Manifest =
        serde_json::from_value(study).map_err(|source| StudyError::Parse { path: file.clone(), line: 0, source })?;
    if m.umbra_version != run.umbra_version {
        return Err(refuse(
            &file,
            format!(
                "its record says version {} and its study record {}: one run writes both",
                run.umbra_version, m.umbra_version
            ),
        ));
    }
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
            ("clipped_area_px", m.clipped_area_px),
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
        let classes = [m.aliasing_px, m.penumbra_px, m.acne_px, m.detachment_px, m.leaks_px, m.clipped_px];
        let wrong = classes.iter().try_fold(0u64, |a, &n| a.checked_add(n));
        if wrong.is_none_or(|n| n > m.evaluated_px) {
            return Some(
                "more wrong pixels (aliasing, penumbra, acne, detachment, leaks, clipped) than evaluated".into(),
            );
        }
        if wrong.is_none_or(|n| m.receiver_fallback_px > n) {
            return Some("more receiver fallbacks than wrong pixels".into());
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
