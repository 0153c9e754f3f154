//! The speed/accuracy trade study: a sweep over scene × shadow algorithm ×
//! depth format × map size × filter × architecture preset, each
//! configuration rendered once against the exact reference and costed on
//! every preset.
//!
//! What each algorithm buys is the papers' question: Williams' first depth
//! over a bias sweep (Reeves et al. §4), Wang & Molnar's second depth with and
//! without virtual samples and by front-face culling (§3), Woo's midpoint,
//! and Weiskopf & Ertl's dual depth over an offset sweep (§3), with and
//! without their per-object back-face culling, Sen et al.'s silhouette maps
//! and stencil shadow volumes (§2, §5). What it costs is counted by
//! the architecture presets of [`crate::cost::arch`] and the timing model of
//! [`crate::cost::timing`] (Sen et al.'s §5 bandwidth
//! question, per buffer).
//!
//! Rows are sorted by configuration index and preset, whatever the thread
//! count or timing, so the output bytes are a function of the sweep alone.
//! `--shard i/n` runs every `n`-th block of configurations that share
//! their passes ([`Layout`], [`Shard`]);
//! [`merge`] reads shard outputs back and writes exactly the files of the
//! whole run.

use std::path::PathBuf;

use crate::experiment::plot::PlotError;
use crate::input::limits::FileError;
use crate::output::OutputError;
use crate::world::scene_file::SceneError;

pub mod budget;
pub(crate) mod extremes;
mod headline;
pub mod objective;
pub(crate) mod plot;
mod rank;

mod request;
mod row;
mod run;
pub mod schema;
mod shards;
mod summary;
mod sweep;
mod sweep_file;

pub use crate::cost::report::stats::RowCost;
use budget::{Budget, Measure};
pub use headline::headline;
pub use request::{Outcome, Overrides, Prepared, Request, choose_archs, image_size, map_sides, no_repeats};
pub use row::{Row, RowConfig, RowMetrics, Status};
#[cfg(test)]
use run::run_unshared;
use run::sort_rows;
pub use run::{load_scenes, render_config, run};
use shards::jsonl;
#[cfg(test)]
use shards::write_run;
pub use shards::{Manifest, ShardFolder, ShardProblem, ShardState, ShardStatus};
pub(crate) use shards::{already_complete, finish, write_partial};
pub use shards::{merge, merge_replacing, read_rows, status};
pub(crate) use summary::write_outputs;
pub use summary::{summary, table};
#[cfg(test)]
use sweep::jittered;
pub use sweep::{ArchPoint, Config, Layout, MAX_ARCHITECTURES, MAX_CONFIGURATIONS, Shard, Spec, Variant};
pub use sweep_file::{SweepError, SweepFile};

/// The distinct `values`, in order of first appearance (scenes, families,
/// architecture points as the rows list them).
fn distinct<T: PartialEq>(values: impl IntoIterator<Item = T>) -> Vec<T> {
    let mut out = Vec::new();
    for v in values {
        if !out.contains(&v) {
            out.push(v);
        }
    }
    out
}

/// Most error budgets a study takes (each is a line on every plot and a
/// column of every table).
pub(crate) const MAX_BUDGETS: usize = 16;

/// Why a list of error budgets is unusable, if it is: more than
/// [`MAX_BUDGETS`], a value that is not a percentage in (0, 100], or one
/// given twice. The message names the offending entry by its index.
#[must_use]
pub(crate) fn budgets_problem(budgets: &[Budget]) -> Option<(usize, String)> {
    if budgets.len() > MAX_BUDGETS {
        return Some((MAX_BUDGETS, format!("{} budgets; at most {MAX_BUDGETS}", budgets.len())));
    }
    if let Some((i, b)) =
        budgets.iter().enumerate().find(|&(_, b)| !(b.percent.is_finite() && b.percent > 0.0 && b.percent <= 100.0))
    {
        return Some((i, format!("{} is not a percentage in (0, 100]", b.percent)));
    }
    repeated(budgets).map(|(j, i)| (i, format!("{} repeats budget {j}", budgets[i])))
}

/// The first value of `items` that repeats an earlier one: `(earlier, later)` indices.
pub(super) fn repeated<T: PartialEq>(items: &[T]) -> Option<(usize, usize)> {
    items.iter().enumerate().find_map(|(k, x)| items[..k].iter().position(|y| y == x).map(|j| (j, k)))
}

/// Two scenes of one name, if there are: `(earlier, later, problem)`.
/// Rows, the summary's sections and merged shards tell scenes apart by
/// name, so two files that both call themselves `table` would be one.
fn same_names(scenes: &[crate::world::scene::Scene]) -> Option<(usize, usize, String)> {
    let names: Vec<&str> = scenes.iter().map(|s| s.name.as_str()).collect();
    repeated(&names).map(|(first, again)| {
        let (a, b) = (&scenes[first], &scenes[again]);
        (
            first,
            again,
            format!("`{}` and `{}` are both named `{}`; rename one (its `name` key)", a.source, b.source, a.name),
        )
    })
}

/// The budget the summary's crossovers and the axes' plot judge winners
/// by: the loosest on artifacts, else the first.
fn loosest(budgets: &[Budget]) -> Option<Budget> {
    let artifacts = budgets.iter().filter(|b| b.measure == Measure::Artifacts);
    artifacts.max_by(|a, b| a.percent.total_cmp(&b.percent)).or(budgets.first()).copied()
}

/// Why the study could not run or write its files.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudyError {
    /// A scene could not be loaded.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A sweep file is unusable.
    #[error(transparent)]
    Sweep(#[from] SweepError),
    /// The study would take more memory than the limits allow.
    #[error(transparent)]
    Limit(#[from] crate::input::limits::LimitError),
    /// A `--shard` argument is not `i/n` with `i < n`.
    #[error("--shard `{0}`: expected i/n with 0 ≤ i < n")]
    Shard(String),
    /// A file could not be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A results file could not be read, is not a regular file, or is
    /// larger than [`Limits::max_file_bytes`](crate::input::limits::Limits::max_file_bytes).
    #[error("{path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: FileError,
    },
    /// A line of a results file is not a study row.
    #[error("{path}:{line}: not a study row: {source}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The line (from 1).
        line: usize,
        /// The parser's error.
        source: serde_json::Error,
    },
    /// Shards that cannot be merged into a run that tells the truth.
    #[error("{path}: {problem}")]
    Merge {
        /// The file at fault (the output folder for what is missing).
        path: PathBuf,
        /// What is wrong.
        problem: String,
    },
    /// A plot could not be drawn.
    #[error("plot {path}: {problem}")]
    Plot {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        problem: String,
    },
    /// What a host asked for is unusable: the message names the flag and
    /// the value.
    #[error("{0}")]
    Request(String),
    /// An architecture did not load, or refused a change.
    #[error(transparent)]
    Arch(#[from] crate::cost::arch::ArchError),
    /// A stop was requested before the study finished.
    #[error(transparent)]
    Stopped(#[from] crate::base::stop::Stopped),
}

impl From<PlotError> for StudyError {
    fn from(e: PlotError) -> Self {
        match e {
            PlotError::Draw { path, problem } => Self::Plot { path, problem },
            PlotError::Output(e) => Self::Output(e),
        }
    }
}

#[cfg(test)]
mod tests;
