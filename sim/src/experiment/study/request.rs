//! A study as a host asks for it — a sweep, the axes it replaces, a shard,
//! the output folder — checked, hashed and run here, once, for the command
//! line and Python alike ([`Request::prepare`], [`Prepared::run`]).
//!
//! The hash that decides which shards may merge is the sweep file's own,
//! or, when axes are replaced, the hash of the file and of the replaced
//! axes written canonically ([`Overrides::canonical`]): the same request
//! spelled in another order of flags, or by another host, hashes the same.

use crate::experiment::study::budget::{Budget, Measure};
use crate::experiment::study::objective::CostLimits;
use std::path::PathBuf;

use indicatif::ProgressBar;
use umbra_core::RasterConfig;

use super::sweep_file::MAX_AXIS_VALUES;
use super::{
    Manifest, Row, Shard, Spec, StudyError, SweepFile, already_complete, budgets_problem, extremes, finish,
    load_scenes, repeated, run, summary, write_outputs, write_partial,
};
use crate::cost::arch::Arch;
use crate::input::limits::Limits;
use crate::output::folder::{Claim, OutputFolder, Replaced, RunKind};
use crate::output::provenance::hash;

/// The axes a host replaces in a sweep file, each empty (or `None`) to
/// keep the file's.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Scenes: bundled names or scene files.
    pub scenes: Vec<String>,
    /// Architectures: bundled names, files, or `all`.
    pub archs: Vec<String>,
    /// `key=value` changes to every architecture (the file's when
    /// `archs` is empty).
    pub sets: Vec<String>,
    /// Image sizes, `WIDTHxHEIGHT`.
    pub images: Vec<String>,
    /// Reference rays per pixel side.
    pub reference_rays: Option<u32>,
    /// Error budgets, each on a measure of the metrics.
    pub budgets: Vec<Budget>,
    /// Map sides.
    pub maps: Vec<u32>,
    /// The most the summary's best per objective may cost.
    pub cost_limits: CostLimits,
}

impl Overrides {
    /// Whether it replaces nothing.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// The replaced axes written canonically, one `axis=value,value` a
    /// line in a fixed order and spelling, for the hash: independent of
    /// the struct's field names and of any `Debug` output.
    #[must_use]
    pub fn canonical(&self) -> String {
        let list = |v: &[String]| v.join(",");
        let numbers = |v: Vec<String>| v.join(",");
        [
            format!("scenes={}", list(&self.scenes)),
            format!("arch={}", list(&self.archs)),
            format!("set={}", list(&self.sets)),
            format!("image={}", list(&self.images)),
            format!("reference_rays={}", self.reference_rays.map(|n| n.to_string()).unwrap_or_default()),
            // An artifacts budget as a bare number, as the hash always had it.
            format!(
                "budgets={}",
                numbers(
                    self.budgets
                        .iter()
                        .map(|b| if b.measure == Measure::Artifacts { b.percent.to_string() } else { b.to_string() })
                        .collect()
                )
            ),
            format!("maps={}", numbers(self.maps.iter().map(u32::to_string).collect())),
        ]
        .into_iter()
        // Cost limits change the summary: a line each, when set (so that
        // the hashes of earlier requests stay as they were).
        .chain(self.cost_limits.max_square_metres.map(|m| format!("max_area={m:e}")))
        .chain(self.cost_limits.max_joules.map(|m| format!("max_energy={m:e}")))
        .collect::<Vec<_>>()
        .join("\n")
    }
}

/// A study asked for.
#[derive(Clone, Debug)]
pub struct Request {
    /// A bundled sweep's name or a sweep file.
    pub sweep: String,
    /// The axes replaced.
    pub overrides: Overrides,
    /// The shard to run (`i/n`), or the whole sweep.
    pub shard: Option<String>,
    /// Also run the numerical extremes.
    pub extremes: bool,
    /// The output folder.
    pub out: PathBuf,
    /// Replace another command's results in `out`, or files no run of
    /// Umbra wrote there, deliberately ([`Claim::replace`]).
    pub replace: bool,
}

/// A request checked: the sweep, every axis it replaces, the shard and
/// the memory the study takes at `threads` renders at once, all before
/// any folder is made.
#[derive(Debug)]
pub struct Prepared {
    /// The sweep file.
    pub file: SweepFile,
    /// The sweep, its axes replaced, with its hash.
    pub spec: Spec,
    /// The shard.
    pub shard: Shard,
    /// Whether the extremes run too.
    pub extremes: bool,
    /// The output folder.
    pub out: PathBuf,
    /// Replace what is in it ([`Request::replace`]).
    pub replace: bool,
}

/// What a prepared study did.
#[derive(Debug)]
pub enum Outcome {
    /// The shard's folder already held it, complete and verified, of this
    /// sweep and version: nothing was recomputed.
    AlreadyComplete(Manifest),
    /// It ran.
    Ran {
        /// The rows.
        rows: Vec<Row>,
        /// Its manifest.
        manifest: Manifest,
        /// The summary (the whole sweep only).
        summary: Option<String>,
        /// The extremes' report, when asked for.
        extremes: Option<String>,
        /// What it replaced in its folder.
        replaced: Replaced,
    },
}

/// `flag`'s `items`, at most 4096 of them (as a sweep file's axis), with
/// none given twice.
///
/// # Errors
/// [`StudyError::Request`] naming the flag and the item, or the count.
pub fn no_repeats<'a>(flag: &str, items: impl IntoIterator<Item = &'a str>) -> Result<(), StudyError> {
    let mut seen = std::collections::BTreeSet::new();
    let mut items = items.into_iter();
    while let Some(item) = items.next() {
        if seen.len() == MAX_AXIS_VALUES {
            let n = MAX_AXIS_VALUES + 1 + items.count();
            return Err(StudyError::Request(format!(
                "{flag}: {n} values; a list has at most {MAX_AXIS_VALUES}, as a sweep's axis"
            )));
        }
        if !seen.insert(item) {
            return Err(StudyError::Request(format!("{flag} `{item}` is given twice")));
        }
    }
    Ok(())
}

/// Map sides a study or plan sweeps: a list within [`no_repeats`], each
/// side within the limits and a map the rasterizer takes.
///
/// # Errors
/// [`StudyError::Request`] naming `flag`, the side and the limit
/// (`--max-map-side`) it breaks.
pub fn map_sides(flag: &str, sides: &[u32], limits: &Limits) -> Result<(), StudyError> {
    let names: Vec<String> = sides.iter().map(u32::to_string).collect();
    no_repeats(flag, names.iter().map(String::as_str))?;
    for &side in sides {
        let bad = |why: String| StudyError::Request(format!("{flag} {side}: {why}"));
        limits.check_map(side).map_err(|e| bad(format!("{e}; raise it with --max-map-side")))?;
        RasterConfig::new(side, side, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
            .map_err(|e| bad(e.to_string()))?;
    }
    Ok(())
}

/// A `WIDTHxHEIGHT` image size within the limits.
///
/// # Errors
/// [`StudyError::Request`] naming the size.
pub fn image_size(text: &str, limits: &Limits) -> Result<[u32; 2], StudyError> {
    let bad = |why: String| StudyError::Request(format!("--image {text}: {why}"));
    let (w, h) = text
        .split_once(['x', '×'])
        .and_then(|(w, h)| Some((w.trim().parse::<u32>().ok()?, h.trim().parse::<u32>().ok()?)))
        .ok_or_else(|| StudyError::Request(format!("--image `{text}`: expected WIDTHxHEIGHT, e.g. 640x360")))?;
    limits.check_image(w, h).map_err(|e| bad(e.to_string()))?;
    RasterConfig::new(w, h, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
        .map_err(|e| bad(e.to_string()))?;
    Ok([w, h])
}

/// The architectures `names` choose (bundled names, files, or `all` for
/// every bundled one; `default` when there are none), each with the
/// `key=value` changes `sets`, named in its name ([`Arch::set_named`]).
///
/// # Errors
/// [`StudyError::Request`] for an architecture chosen twice or a key set
/// twice; [`StudyError::Arch`] for one that does not load or a change it
/// refuses.
pub fn choose_archs(
    names: &[String],
    sets: &[String],
    default: &[&str],
    limits: &Limits,
) -> Result<Vec<Arch>, StudyError> {
    let names: Vec<&str> = if names.is_empty() { default.to_vec() } else { names.iter().map(String::as_str).collect() };
    let mut archs: Vec<Arch> = Vec::new();
    for name in names {
        let more = if name == "all" { Arch::presets()? } else { vec![Arch::open(name, limits)?] };
        for arch in more {
            if archs.iter().any(|a| a.name == arch.name) {
                return Err(StudyError::Request(format!(
                    "--arch {name}: architecture `{}` is chosen twice",
                    arch.name
                )));
            }
            archs.push(arch);
        }
    }
    no_repeats("--set", sets.iter().map(|s| s.split_once('=').map_or(s.as_str(), |(k, _)| k.trim())))?;
    for arch in &mut archs {
        for s in sets {
            arch.set_named(s)?;
        }
    }
    Ok(archs)
}

impl Request {
    /// The request checked, before anything is written: the sweep loaded,
    /// every replaced axis checked against the limits, the sweep's size,
    /// the shard, and the memory of `threads` renders at once.
    ///
    /// # Errors
    /// [`StudyError`] naming what is wrong.
    pub fn prepare(&self, limits: &Limits, threads: usize) -> Result<Prepared, StudyError> {
        self.prepare_file(SweepFile::open(&self.sweep, limits)?, limits, threads)
    }

    /// [`prepare`](Self::prepare) of a sweep file already read (a host's
    /// own text, named `file`), in place of `sweep`.
    ///
    /// # Errors
    /// [`StudyError`] naming what is wrong.
    pub fn prepare_file(&self, file: SweepFile, limits: &Limits, threads: usize) -> Result<Prepared, StudyError> {
        let o = &self.overrides;
        no_repeats("scene", o.scenes.iter().map(String::as_str))?;
        map_sides("--maps", &o.maps, limits)?;
        no_repeats("--image", o.images.iter().map(String::as_str))?;
        let mut spec = file.spec(limits)?;
        if !o.scenes.is_empty() {
            spec.scenes = load_scenes(&o.scenes, limits)?;
        }
        if o.archs.is_empty() {
            // A key the sweep's axes vary is theirs: a change to every point
            // would leave each point's record naming a value it does not run.
            for s in &o.sets {
                let key = s.split_once('=').map_or(s.as_str(), |(k, _)| k.trim());
                if spec.arch_points.iter().any(|p| p.assignments.iter().any(|(k, _)| k == key)) {
                    return Err(StudyError::Request(format!(
                        "--set {s}: the sweep's arch_axes vary `{key}`; change its values there"
                    )));
                }
            }
            for arch in &mut spec.archs {
                for s in &o.sets {
                    arch.set_named(s)?;
                }
            }
        } else {
            spec.archs = choose_archs(&o.archs, &o.sets, &[], limits)?;
            spec.arch_points.clear();
        }
        if !o.images.is_empty() {
            let sizes: Vec<[u32; 2]> = o.images.iter().map(|i| image_size(i, limits)).collect::<Result<_, _>>()?;
            if let Some((first, again)) = repeated(&sizes) {
                let [w, h] = sizes[first];
                return Err(StudyError::Request(format!(
                    "--image `{}` and `{}` are one size, {w}x{h}: give it once",
                    o.images[first], o.images[again]
                )));
            }
            spec.images = sizes;
        }
        if let Some(n) = o.reference_rays {
            if !crate::render::RenderConfig::REFERENCE_RAYS.contains(&n) {
                let range = crate::render::RenderConfig::REFERENCE_RAYS;
                return Err(StudyError::Request(format!("--reference-rays {n} is outside {range:?}")));
            }
            spec.reference_rays = n;
        }
        if !o.budgets.is_empty() {
            if let Some((_, problem)) = budgets_problem(&o.budgets) {
                return Err(StudyError::Request(format!("--budgets: {problem}")));
            }
            spec.budgets.clone_from(&o.budgets);
        }
        if !o.maps.is_empty() {
            spec.map_sizes.clone_from(&o.maps);
        }
        spec.cost_limits = o.cost_limits;
        // Replaced axes change the sweep: its hash covers them, so shards
        // run with different ones do not merge.
        if !o.is_empty() {
            spec.hash = hash(format!("{}\n{}", file.text, o.canonical()).as_bytes());
        }
        spec.limits = *limits;
        if let Some(problem) = spec.size_problem() {
            return Err(StudyError::Request(format!("the sweep with these flags: {problem}")));
        }
        let shard = self.shard.as_deref().map(Shard::parse).transpose()?.unwrap_or(Shard::ALL);
        spec.renders_at_once(threads)?;
        Ok(Prepared { file, spec, shard, extremes: self.extremes, out: self.out.clone(), replace: self.replace })
    }
}

impl Prepared {
    /// Run it into its folder: the rows (or, of a shard, its partial rows),
    /// the sweep file, the effective architectures and, when asked, the
    /// extremes; the manifest last. A shard whose folder already holds it,
    /// complete and verified, is not recomputed.
    ///
    /// # Errors
    /// [`StudyError`] from a write or from the extremes.
    pub fn run(&self, progress: &ProgressBar) -> Result<Outcome, StudyError> {
        let (spec, shard, out) = (&self.spec, self.shard, self.out.as_path());
        let expected = Manifest::new(spec, shard, 0);
        if shard != Shard::ALL && already_complete(out, &expected, &spec.limits) {
            return Ok(Outcome::AlreadyComplete(expected));
        }
        let mut folder = OutputFolder::create(out, Claim::new(RunKind::Study).replacing(self.replace))?;
        let rows = run(spec, shard, progress)?;
        let manifest = Manifest::new(spec, shard, rows.len());
        if shard == Shard::ALL {
            write_outputs(&mut folder, &rows, &manifest)?;
        } else {
            write_partial(&mut folder, &rows)?;
        }
        folder.write_text("sweep.toml", &self.file.text)?;
        // The effective architectures, beside the rows that name them.
        for arch in &spec.archs {
            folder.write_text(&format!("arch-{}.toml", arch.name), &arch.to_toml())?;
        }
        let extremes = if self.extremes { Some(extremes::run_all(&mut folder, &spec.limits)?) } else { None };
        let (_, replaced) = finish(folder, &manifest)?;
        let summary = (shard == Shard::ALL).then(|| summary(&rows, &manifest));
        Ok(Outcome::Ran { rows, manifest, summary, extremes, replaced })
    }
}
