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
//! the architecture presets of [`crate::arch`] (Sen et al.'s §5 bandwidth
//! question, per buffer).
//!
//! Rows are sorted by configuration index and preset, whatever the thread
//! count or timing, so the output bytes are a function of the sweep alone.
//! `--shard i/n` runs the configurations whose index is `i` modulo `n`;
//! [`merge`] reads shard outputs back and writes exactly the files of the
//! whole run.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use indicatif::ProgressBar;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use umbra_core::DepthFormatKind;
use umbra_core::shadow::{Filter, Jitter};

use crate::arch::{ArchParams, CostReport};
use crate::limits::{FileError, Limits};
use crate::metrics::Metrics;
use crate::output::{OutputError, write_text};
use crate::reference::PixelTruth;
use crate::render::{Algorithm, RenderConfig, cost_within, render_against, truth};
use crate::scene::Scene;
use crate::scene_file::SceneError;

pub mod extremes;
pub mod plot;

/// Which objects the light pass may cull for an algorithm that culls.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Culling {
    /// As the algorithm does it: solids culled, open surfaces not
    /// (Weiskopf & Ertl §3.2).
    Scene,
    /// Every object treated as open, so nothing is culled (the comparison
    /// Weiskopf & Ertl's Figure 6 makes).
    Off,
}

/// One point on the study's algorithm axis: a shadow algorithm with its
/// bias, virtual samples and culling.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// A short name for tables and files (`first`, `second-novs`, …).
    pub name: &'static str,
    /// The algorithm.
    pub algorithm: Algorithm,
    /// The bias, as a depth in `[0, 1]`.
    pub bias: f64,
    /// Wang & Molnar's virtual samples (second depth only).
    pub virtual_samples: bool,
    /// The light pass's culling.
    pub culling: Culling,
}

impl Variant {
    /// An algorithm at a bias, virtual samples on, the algorithm's own culling.
    #[must_use]
    pub const fn new(name: &'static str, algorithm: Algorithm, bias: f64) -> Self {
        Self { name, algorithm, bias, virtual_samples: true, culling: Culling::Scene }
    }

    /// The same with virtual samples off.
    #[must_use]
    pub const fn without_virtual_samples(mut self) -> Self {
        self.virtual_samples = false;
        self
    }

    /// The same with nothing culled.
    #[must_use]
    pub const fn without_culling(mut self) -> Self {
        self.culling = Culling::Off;
        self
    }

    /// Reeves' `Bias1`, if the algorithm draws its bias from a range.
    #[must_use]
    pub const fn bias_hi(&self) -> Option<f64> {
        match self.algorithm {
            Algorithm::BiasRange { hi } => Some(hi),
            _ => None,
        }
    }

    /// The dual offset, if the algorithm has one.
    #[must_use]
    pub const fn offset(&self) -> Option<f64> {
        match self.algorithm {
            Algorithm::Dual { offset } => Some(offset),
            _ => None,
        }
    }
}

/// First-depth biases of the full sweep (depths in `[0, 1]`): from none,
/// through the acne-free range of the bundled scenes, to clearly too much.
pub const FIRST_BIASES: [f64; 7] = [0.0, 0.0002, 0.0005, 0.001, 0.002, 0.005, 0.01];

/// Reeves et al.'s bias ranges `[Bias0, Bias1]` of the full sweep (depths
/// in `[0, 1]`), around the acne-free constant biases.
pub const BIAS_RANGES: [(f64, f64); 3] = [(0.0002, 0.001), (0.0005, 0.002), (0.001, 0.005)];

/// Dual-depth offsets of the full sweep (Weiskopf & Ertl's `z_offset`).
pub const DUAL_OFFSETS: [f64; 3] = [0.001, 0.005, 0.02];

/// Woo's midpoint computed by the dual test with an unlimited offset:
/// `z1 + min((z2 − z1)/2, 1) = (z1 + z2)/2`, which lets the midpoint run
/// with Weiskopf & Ertl's per-object back-face culling.
pub const UNLIMITED_OFFSET: f64 = 1.0;

/// The study's algorithm axis. Adding an algorithm to the sweep is one line
/// here.
#[must_use]
pub fn algorithms(quick: bool) -> Vec<Variant> {
    let biases: &[f64] = if quick { &[0.0, 0.001, 0.005] } else { &FIRST_BIASES };
    let offsets: &[f64] = if quick { &[0.005] } else { &DUAL_OFFSETS };
    let mut v: Vec<Variant> = biases.iter().map(|&b| Variant::new("first", Algorithm::First, b)).collect();
    let ranges: &[(f64, f64)] = if quick { &BIAS_RANGES[1..2] } else { &BIAS_RANGES };
    v.extend(ranges.iter().map(|&(lo, hi)| Variant::new("first-range", Algorithm::BiasRange { hi }, lo)));
    v.push(Variant::new("second", Algorithm::Second, 0.0));
    v.push(Variant::new("second-novs", Algorithm::Second, 0.0).without_virtual_samples());
    v.push(Variant::new("second-ffc", Algorithm::SecondFrontCulled, 0.0));
    v.push(Variant::new("midpoint", Algorithm::Midpoint, 0.0));
    v.push(Variant::new("midpoint-bfc", Algorithm::Dual { offset: UNLIMITED_OFFSET }, 0.0));
    v.extend(offsets.iter().map(|&offset| Variant::new("dual", Algorithm::Dual { offset }, 0.0)));
    v.push(Variant::new("dual-nocull", Algorithm::Dual { offset: offsets[0] }, 0.0).without_culling());
    v.push(Variant::new("silhouette", Algorithm::Silhouette { packed: false }, SILHOUETTE_BIAS));
    v.push(Variant::new("silhouette-packed", Algorithm::Silhouette { packed: true }, SILHOUETTE_BIAS));
    v.push(Variant::new("volumes", Algorithm::Volumes, 0.0));
    v
}

/// The bias of the first-depth map under Sen et al.'s silhouette map (the
/// study's middle first-depth bias).
pub const SILHOUETTE_BIAS: f64 = 0.002;

/// Reeves' jittered filter with `n` samples per lookup, his other Figure 4
/// parameters unchanged.
#[must_use]
pub fn jittered(n: u16) -> Filter {
    Filter::Jittered(Jitter { num_samples: n, ..Jitter::REEVES })
}

/// The sweep's axes.
#[derive(Clone, Debug)]
pub struct Spec {
    /// Scenes, each rendered with its first light.
    pub scenes: Vec<Scene>,
    /// Algorithms.
    pub variants: Vec<Variant>,
    /// Depth formats of the map.
    pub formats: Vec<DepthFormatKind>,
    /// Map sides in texels.
    pub map_sizes: Vec<u32>,
    /// Filters, with their names.
    pub filters: Vec<(String, Filter)>,
    /// Architecture presets; none: metrics only, one row per configuration.
    pub archs: Vec<ArchParams>,
    /// Camera image width.
    pub width: u32,
    /// Camera image height.
    pub height: u32,
    /// Reference rays per pixel side.
    pub reference_samples: u32,
    /// What each render may ask for: a configuration beyond them is a
    /// skipped row that says which limit.
    pub limits: Limits,
}

/// The scenes of `--quick`: Wang & Molnar's table, Weiskopf & Ertl's L and
/// Reeves' sphere.
pub const QUICK_SCENES: [&str; 3] = ["table", "weiskopf-l", "reeves-sphere"];

impl Spec {
    /// The full sweep over `scenes`: every algorithm, d16/d24/f32, maps of
    /// 64 … 2048 texels, the five filters of [`crate::presets::FILTERS`],
    /// the three presets, 320×180 images against 4×4 reference rays.
    #[must_use]
    pub fn full(scenes: Vec<Scene>) -> Self {
        Self {
            scenes,
            variants: algorithms(false),
            formats: vec![DepthFormatKind::D16, DepthFormatKind::D24, DepthFormatKind::F32],
            map_sizes: vec![64, 128, 256, 512, 1024, 2048],
            filters: crate::presets::FILTERS.iter().map(|(n, f)| ((*n).to_owned(), *f)).collect(),
            archs: ArchParams::PRESETS.to_vec(),
            width: 320,
            height: 180,
            reference_samples: 4,
            limits: Limits::DEFAULT,
        }
    }

    /// The `--quick` sweep: fewer biases and offsets, d16 and d24, 256² and
    /// 1024² maps, point and bilinear filters, 160×90 images against 2×2
    /// reference rays.
    #[must_use]
    pub fn quick(scenes: Vec<Scene>) -> Self {
        Self {
            variants: algorithms(true),
            formats: vec![DepthFormatKind::D16, DepthFormatKind::D24],
            map_sizes: vec![256, 1024],
            filters: crate::presets::FILTERS
                .iter()
                .filter(|(n, _)| matches!(*n, "point" | "bilinear"))
                .map(|(n, f)| ((*n).to_owned(), *f))
                .collect(),
            width: 160,
            height: 90,
            reference_samples: 2,
            ..Self::full(scenes)
        }
    }

    /// Every configuration, in the fixed order that numbers them: scene,
    /// algorithm, format, map size, filter.
    #[must_use]
    pub fn configs(&self) -> Vec<Config> {
        let mut out = Vec::new();
        for scene in 0..self.scenes.len() {
            for variant in 0..self.variants.len() {
                for &format in &self.formats {
                    for &map_size in &self.map_sizes {
                        for filter in 0..self.filters.len() {
                            out.push(Config { index: out.len(), scene, variant, format, map_size, filter });
                        }
                    }
                }
            }
        }
        out
    }
}

/// One render configuration of a [`Spec`] (indices into its axes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Config {
    /// Position in [`Spec::configs`].
    pub index: usize,
    /// Scene.
    pub scene: usize,
    /// Algorithm.
    pub variant: usize,
    /// Depth format.
    pub format: DepthFormatKind,
    /// Map side.
    pub map_size: u32,
    /// Filter.
    pub filter: usize,
}

/// A deterministic partition of the configurations: shard `index` of
/// `count` runs those whose index is `index` modulo `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0..count`.
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

impl Shard {
    /// The whole sweep.
    pub const ALL: Self = Self { index: 0, count: 1 };

    /// Read `i/n`.
    ///
    /// # Errors
    /// [`StudyError::Shard`] unless `i` and `n` are integers with `i < n`.
    pub fn parse(s: &str) -> Result<Self, StudyError> {
        let bad = || StudyError::Shard(s.to_owned());
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count) = (i.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// Whether this shard runs configuration `index`.
    #[must_use]
    pub const fn contains(self, index: usize) -> bool {
        index % self.count == self.index
    }
}

/// Why the study could not run or write its files.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudyError {
    /// A scene could not be loaded.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A `--shard` argument is not `i/n` with `i < n`.
    #[error("--shard `{0}`: expected i/n with 0 ≤ i < n")]
    Shard(String),
    /// A file could not be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A results file could not be read, is not a regular file, or is
    /// larger than [`Limits::max_file_bytes`].
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
    /// Two shards hold the same row.
    #[error("row {index} ({arch}) appears twice among the merged files (overlapping shards?)")]
    Duplicate {
        /// The configuration index.
        index: usize,
        /// The preset.
        arch: String,
    },
    /// CSV encoding failed.
    #[error("results.csv: {0}")]
    Csv(#[from] csv::Error),
    /// A plot could not be drawn.
    #[error("plot {path}: {problem}")]
    Plot {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        problem: String,
    },
}

/// One configuration on one architecture: every metric and every cost.
/// Numbers are absent when the render or the costing was skipped (`status`
/// and `reason` say why).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// The configuration's index in the sweep.
    pub index: usize,
    /// The preset's position in the sweep (sort key).
    pub arch_index: usize,
    /// Scene name.
    pub scene: String,
    /// Algorithm name ([`Variant::name`]).
    pub algorithm: String,
    /// Bias, depth in `[0, 1]`.
    pub bias: f64,
    /// Dual offset, for dual depth.
    pub offset: Option<f64>,
    /// Reeves' `Bias1`, for a bias range (`bias` is `Bias0`).
    pub bias_hi: Option<f64>,
    /// Virtual samples on.
    pub virtual_samples: bool,
    /// Culling.
    pub culling: Culling,
    /// Depth format.
    pub format: String,
    /// Map side.
    pub map: u32,
    /// Filter name.
    pub filter: String,
    /// Architecture preset (`-` when the sweep has none).
    pub arch: String,
    /// Camera image width.
    pub width: u32,
    /// Camera image height.
    pub height: u32,
    /// Reference rays per pixel side.
    pub reference_samples: u32,
    /// `ok` or `skipped`.
    pub status: String,
    /// Why the row was skipped (empty when ok).
    pub reason: String,
    /// Pixels compared (facing the light).
    pub evaluated: Option<u64>,
    /// Misclassified, percent of the evaluated pixels.
    pub misclassified_percent: Option<f64>,
    /// False shadows (acne, self-shadowing) per evaluated pixel.
    pub false_shadow_rate: Option<f64>,
    /// False light (leaks, self-unshadowing) per evaluated pixel.
    pub false_light_rate: Option<f64>,
    /// Mean |shadow fraction − true shadowed area|.
    pub mean_abs_error: Option<f64>,
    /// Light pass: setup cycles.
    pub light_setup_cycles: Option<u64>,
    /// Light pass: raster cycles.
    pub light_raster_cycles: Option<u64>,
    /// Light pass: depth-unit cycles.
    pub light_depth_cycles: Option<u64>,
    /// Light pass: resolve cycles.
    pub light_resolve_cycles: Option<u64>,
    /// Light pass bottleneck stage.
    pub light_bottleneck: Option<String>,
    /// Camera pass: setup cycles.
    pub camera_setup_cycles: Option<u64>,
    /// Camera pass: raster cycles.
    pub camera_raster_cycles: Option<u64>,
    /// Camera pass: depth-unit (visibility) cycles.
    pub camera_depth_cycles: Option<u64>,
    /// Camera pass: shadow-unit cycles.
    pub camera_shadow_cycles: Option<u64>,
    /// Camera pass bottleneck stage.
    pub camera_bottleneck: Option<String>,
    /// Light bottleneck plus camera bottleneck cycles (the passes run one
    /// after the other, each as slow as its slowest stage).
    pub total_cycles: Option<u64>,
    /// DRAM: map texels written by the light pass.
    pub dram_map_writes: Option<u64>,
    /// DRAM: depth read back by the light pass.
    pub dram_map_rmw_reads: Option<u64>,
    /// DRAM: bins and setup records of both passes.
    pub dram_bins: Option<u64>,
    /// DRAM: camera-pass visibility depth, when off chip.
    pub dram_camera_depth: Option<u64>,
    /// DRAM: map bytes the shadow unit requested.
    pub dram_map_reads_requested: Option<u64>,
    /// DRAM: map bytes fetched through the preset's cache.
    pub dram_map_reads_fetched: Option<u64>,
    /// DRAM: silhouette points written and read (fetched through the cache
    /// when the preset has one, with the map reads).
    pub dram_silhouette: Option<u64>,
    /// DRAM: scene depth read by shadow-volume fragments.
    pub dram_volume_depth: Option<u64>,
    /// DRAM: stencil read and written by shadow-volume fragments.
    pub dram_stencil: Option<u64>,
    /// All DRAM bytes (fetched map reads, not requested).
    pub total_bytes: Option<u64>,
    /// On-chip depth storage.
    pub on_chip_bytes: Option<u64>,
    /// Light-pass max-z cull rate.
    pub light_cull_rate: Option<f64>,
    /// Camera visibility max-z cull rate.
    pub camera_cull_rate: Option<f64>,
    /// Shadow lookups culled per pixel.
    pub lookups_culled_per_pixel: Option<f64>,
    /// Fraction of pixels with virtual samples.
    pub virtual_sample_fraction: Option<f64>,
    /// Camera-pass map bytes per pixel.
    pub map_bytes_per_pixel: Option<f64>,
}

impl Row {
    /// A row for `config` with everything but the numbers.
    fn new(spec: &Spec, c: &Config, arch: Option<(usize, &ArchParams)>) -> Self {
        let v = &spec.variants[c.variant];
        Self {
            index: c.index,
            arch_index: arch.map_or(0, |a| a.0),
            scene: spec.scenes[c.scene].name.clone(),
            algorithm: v.name.to_owned(),
            bias: v.bias,
            offset: v.offset(),
            bias_hi: v.bias_hi(),
            virtual_samples: v.virtual_samples,
            culling: v.culling,
            format: c.format.name().to_owned(),
            map: c.map_size,
            filter: spec.filters[c.filter].0.clone(),
            arch: arch.map_or_else(|| "-".to_owned(), |a| a.1.name.to_owned()),
            width: spec.width,
            height: spec.height,
            reference_samples: spec.reference_samples,
            status: "ok".to_owned(),
            reason: String::new(),
            evaluated: None,
            misclassified_percent: None,
            false_shadow_rate: None,
            false_light_rate: None,
            mean_abs_error: None,
            light_setup_cycles: None,
            light_raster_cycles: None,
            light_depth_cycles: None,
            light_resolve_cycles: None,
            light_bottleneck: None,
            camera_setup_cycles: None,
            camera_raster_cycles: None,
            camera_depth_cycles: None,
            camera_shadow_cycles: None,
            camera_bottleneck: None,
            total_cycles: None,
            dram_map_writes: None,
            dram_map_rmw_reads: None,
            dram_bins: None,
            dram_camera_depth: None,
            dram_map_reads_requested: None,
            dram_map_reads_fetched: None,
            dram_silhouette: None,
            dram_volume_depth: None,
            dram_stencil: None,
            total_bytes: None,
            on_chip_bytes: None,
            light_cull_rate: None,
            camera_cull_rate: None,
            lookups_culled_per_pixel: None,
            virtual_sample_fraction: None,
            map_bytes_per_pixel: None,
        }
    }

    fn skip(&mut self, reason: String) {
        self.status = "skipped".to_owned();
        self.reason = reason;
    }

    fn set_metrics(&mut self, m: &Metrics) {
        self.evaluated = Some(m.evaluated);
        self.misclassified_percent = Some(m.misclassified_percent);
        self.false_shadow_rate = Some(m.false_shadow_rate);
        self.false_light_rate = Some(m.false_light_rate);
        self.mean_abs_error = Some(m.mean_abs_error);
    }

    fn set_cost(&mut self, r: &CostReport) {
        let [ls, lr, ld, _, lz] = r.light_cycles;
        let [cs, cr, cd, csh, _] = r.camera_cycles;
        self.light_setup_cycles = Some(ls);
        self.light_raster_cycles = Some(lr);
        self.light_depth_cycles = Some(ld);
        self.light_resolve_cycles = Some(lz);
        self.light_bottleneck = Some(format!("{:?}", r.light_bottleneck.0).to_lowercase());
        self.camera_setup_cycles = Some(cs);
        self.camera_raster_cycles = Some(cr);
        self.camera_depth_cycles = Some(cd);
        self.camera_shadow_cycles = Some(csh);
        self.camera_bottleneck = Some(format!("{:?}", r.camera_bottleneck.0).to_lowercase());
        self.total_cycles = Some(r.total_cycles());
        let (l, c) = (&r.light_dram, &r.camera_dram);
        self.dram_map_writes = Some(l.map_writes);
        self.dram_map_rmw_reads = Some(l.map_rmw_reads);
        self.dram_bins = Some(l.bins + c.bins);
        self.dram_camera_depth = Some(c.map_writes + c.map_rmw_reads);
        self.dram_map_reads_requested = Some(c.map_reads);
        self.dram_map_reads_fetched = Some(r.map_bytes_fetched);
        self.dram_silhouette = Some(l.silhouette_writes + c.silhouette_reads);
        self.dram_volume_depth = Some(c.volume_depth_reads);
        self.dram_stencil = Some(c.stencil);
        self.total_bytes = Some(r.total_bytes());
        self.on_chip_bytes = Some(r.on_chip_bytes);
        self.light_cull_rate = Some(r.max_z_cull_rate[0]);
        self.camera_cull_rate = Some(r.max_z_cull_rate[1]);
        self.lookups_culled_per_pixel = Some(r.lookups_culled_per_pixel);
        self.virtual_sample_fraction = Some(r.virtual_sample_fraction);
        self.map_bytes_per_pixel = Some(r.map_bytes_per_pixel);
    }

    /// Whether the row has both an error and a cost.
    #[must_use]
    pub fn complete(&self) -> bool {
        self.status == "ok" && self.misclassified_percent.is_some() && self.total_cycles.is_some()
    }

    /// The configuration and preset in words, for tables.
    #[must_use]
    pub fn label(&self) -> String {
        format!("{}, {}", self.render_label(), self.arch)
    }

    /// The render configuration in words (no preset).
    #[must_use]
    pub fn render_label(&self) -> String {
        let mut s = self.algorithm.clone();
        if let Some(hi) = self.bias_hi {
            let _ = write!(s, " bias {}…{hi}", self.bias);
        } else if self.algorithm == "first" || self.bias != 0.0 {
            let _ = write!(s, " bias {}", self.bias);
        }
        if let Some(o) = self.offset.filter(|_| self.algorithm.starts_with("dual")) {
            let _ = write!(s, " offset {o}");
        }
        let _ = write!(s, ", {}, {}², {}", self.format, self.map, self.filter);
        s
    }
}

/// The render configuration of `c`.
#[must_use]
pub fn render_config(spec: &Spec, c: &Config) -> RenderConfig {
    let v = &spec.variants[c.variant];
    RenderConfig {
        algorithm: v.algorithm,
        format: c.format,
        map_size: c.map_size,
        filter: spec.filters[c.filter].1,
        bias: v.bias,
        virtual_samples: v.virtual_samples,
        width: spec.width,
        height: spec.height,
        reference_samples: spec.reference_samples,
    }
}

/// `scene` with every object open, so that no light pass culls it.
#[must_use]
pub fn uncullable(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    for o in &mut s.objects {
        o.solid = false;
    }
    s
}

/// Render one configuration once and cost it on every preset: one row per
/// preset (one row when the sweep has none). A render or costing that fails
/// gives skipped rows that say why.
///
/// The render (light pass, camera pass, metrics against the scene's
/// reference from [`truths`]) runs once; each
/// preset re-runs the two passes through its own probe, because a preset's
/// tile size changes the light pass's events (`PixelFlow`'s 128² regions
/// bin and flush differently from 32² chunks), so one recorded event stream
/// cannot stand for all three. The exact reference, the expensive part, is
/// not recomputed.
#[must_use]
pub fn run_config(spec: &Spec, c: &Config, open: &[Scene], truths: &[Truth]) -> Vec<Row> {
    let v = &spec.variants[c.variant];
    let scene = match v.culling {
        Culling::Scene => &spec.scenes[c.scene],
        Culling::Off => &open[c.scene],
    };
    let cfg = render_config(spec, c);
    let metrics = match &truths[c.scene] {
        Ok(t) => render_against(scene, &cfg, t.clone(), &spec.limits).map_err(|e| e.to_string()),
        Err(e) => Err(format!("reference: {e}")),
    };
    let metrics = metrics.map(|r| {
        let t = &r.camera_events.totals;
        (r.metrics, ratio(t.tangent_setups, t.tangent_setups + t.trivial_pixels))
    });
    if spec.archs.is_empty() {
        let mut row = Row::new(spec, c, None);
        match &metrics {
            Ok((m, vs)) => {
                row.set_metrics(m);
                row.virtual_sample_fraction = Some(*vs);
            }
            Err(e) => row.skip(format!("render: {e}")),
        }
        return vec![row];
    }
    spec.archs
        .iter()
        .enumerate()
        .map(|(i, arch)| {
            let mut row = Row::new(spec, c, Some((i, arch)));
            match &metrics {
                Ok((m, _)) => {
                    row.set_metrics(m);
                    match cost_within(scene, &cfg, *arch, &spec.limits) {
                        Ok((report, _)) => row.set_cost(&report),
                        Err(e) => row.skip(format!("cost on {}: {e}", arch.name)),
                    }
                }
                Err(e) => row.skip(format!("render: {e}")),
            }
            row
        })
        .collect()
}

/// A scene's exact reference at the study's image size, or why there is none.
pub type Truth = Result<Vec<Option<PixelTruth>>, String>;

/// The exact reference of every scene of `spec`, built once (in parallel):
/// it depends only on the scene, the image size and the rays per pixel,
/// not on the configuration. Culling changes no geometry, so the scenes
/// with their culling turned off share it.
#[must_use]
pub fn truths(spec: &Spec) -> Vec<Truth> {
    spec.scenes
        .par_iter()
        .map(|scene| {
            truth(scene, spec.width, spec.height, spec.reference_samples, &ProgressBar::hidden())
                .map_err(|e| e.to_string())
        })
        .collect()
}

/// Run the configurations of `shard` in parallel (on the current rayon pool),
/// ticking `progress` once per configuration. Rows come back sorted by
/// configuration and preset.
#[must_use]
pub fn run(spec: &Spec, shard: Shard, progress: &ProgressBar) -> Vec<Row> {
    let open: Vec<Scene> = spec.scenes.iter().map(uncullable).collect();
    let truths = truths(spec);
    let configs: Vec<Config> = spec.configs().into_iter().filter(|c| shard.contains(c.index)).collect();
    progress.set_length(configs.len() as u64);
    let rows: Vec<Vec<Row>> = configs
        .par_iter()
        .map(|c| {
            let rows = run_config(spec, c, &open, &truths);
            progress.inc(1);
            rows
        })
        .collect();
    let mut rows: Vec<Row> = rows.into_iter().flatten().collect();
    sort_rows(&mut rows);
    rows
}

#[allow(clippy::cast_precision_loss, reason = "a ratio of pixel counts")]
fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

fn sort_rows(rows: &mut [Row]) {
    rows.sort_by_key(|r| (r.index, r.arch_index));
}

/// Load scenes by scene file or bundled name ([`Scene::open`]) within `limits`.
///
/// # Errors
/// [`StudyError::Scene`] naming the scene.
pub fn load_scenes<S: AsRef<str>>(names: &[S], limits: &Limits) -> Result<Vec<Scene>, StudyError> {
    names.iter().map(|n| Ok(Scene::open(n.as_ref(), limits)?)).collect()
}

/// The rows as JSON lines.
fn jsonl(rows: &[Row]) -> String {
    let mut s = String::new();
    for r in rows {
        // A Row holds only strings, numbers, booleans and options: it always serialises.
        s.push_str(&serde_json::to_string(r).unwrap_or_default());
        s.push('\n');
    }
    s
}

/// Write a shard's partial `results.jsonl` into `dir`.
///
/// # Errors
/// [`StudyError::Output`].
pub fn write_partial(dir: &Path, rows: &[Row]) -> Result<(), StudyError> {
    write_text(&dir.join("results.jsonl"), &jsonl(rows))?;
    Ok(())
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
    let text = String::from_utf8_lossy(&bytes);
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            serde_json::from_str(l).map_err(|source| StudyError::Parse { path: file.clone(), line: i + 1, source })
        })
        .collect()
}

/// Read shard outputs (folders or files), check that no row appears twice,
/// and write the whole run's files into `out`. Returns the number of rows.
///
/// # Errors
/// See [`StudyError`].
pub fn merge(inputs: &[PathBuf], out: &Path, limits: &Limits) -> Result<usize, StudyError> {
    let mut rows = Vec::new();
    for p in inputs {
        rows.extend(read_rows(p, limits)?);
    }
    sort_rows(&mut rows);
    if let Some(w) = rows.windows(2).find(|w| (w[0].index, w[0].arch_index) == (w[1].index, w[1].arch_index)) {
        return Err(StudyError::Duplicate { index: w[0].index, arch: w[0].arch.clone() });
    }
    write_outputs(out, &rows)?;
    Ok(rows.len())
}

/// The error budgets of the summary, percent misclassified.
pub const BUDGETS: [f64; 3] = [1.0, 0.1, 0.01];

/// Write `results.jsonl`, `results.csv`, the Pareto plots per scene and
/// `summary.md` for a whole run's rows.
///
/// # Errors
/// See [`StudyError`].
pub fn write_outputs(dir: &Path, rows: &[Row]) -> Result<(), StudyError> {
    let mut rows = rows.to_vec();
    sort_rows(&mut rows);
    write_text(&dir.join("results.jsonl"), &jsonl(&rows))?;
    let mut csv = csv::Writer::from_writer(Vec::new());
    for r in &rows {
        csv.serialize(r)?;
    }
    let bytes = csv.into_inner().map_err(|e| StudyError::Csv(e.into_error().into()))?;
    write_text(&dir.join("results.csv"), &String::from_utf8_lossy(&bytes))?;
    for scene in scenes_of(&rows) {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.scene == scene).collect();
        plot::pareto(dir, &scene, &mine)?;
    }
    write_text(&dir.join("summary.md"), &summary(&rows))?;
    Ok(())
}

/// Scene names in order of first appearance.
fn scenes_of(rows: &[Row]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for r in rows {
        if !names.contains(&r.scene) {
            names.push(r.scene.clone());
        }
    }
    names
}

/// The cheapest complete row by `key` whose error is within `budget` percent
/// (ties: the earlier row).
fn cheapest<'a>(rows: &[&'a Row], budget: f64, key: impl Fn(&Row) -> Option<u64>) -> Option<&'a Row> {
    rows.iter()
        .copied()
        .filter(|r| r.complete() && r.misclassified_percent.is_some_and(|m| m <= budget))
        .min_by_key(|r| (key(r).unwrap_or(u64::MAX), r.index, r.arch_index))
}

/// `summary.md`: per scene, the cheapest configuration in cycles and in DRAM
/// bytes under each error budget, and every skipped row's reason.
#[must_use]
pub fn summary(rows: &[Row]) -> String {
    let mut s = String::new();
    let configs = rows.iter().map(|r| r.index).collect::<std::collections::BTreeSet<_>>().len();
    let skipped: Vec<&Row> = rows.iter().filter(|r| r.status != "ok").collect();
    let _ = writeln!(s, "# Umbra study: the cheapest configuration per error budget\n");
    let _ = writeln!(
        s,
        "{} rows ({configs} render configurations × architecture presets), {} skipped. Error: pixels \
         misclassified against the exact reference, percent of those facing the light. Cycles: light-pass \
         plus camera-pass bottleneck. Bytes: all DRAM traffic, map reads as fetched through the preset's cache.\n",
        rows.len(),
        skipped.len()
    );
    for scene in scenes_of(rows) {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.scene == scene).collect();
        let _ = writeln!(s, "## {scene}\n");
        let _ = writeln!(
            s,
            "| error budget | cheapest in cycles | cycles | error % | cheapest in bytes | bytes | error % |"
        );
        let _ = writeln!(s, "|---:|---|---:|---:|---|---:|---:|");
        for budget in BUDGETS {
            let by = |key: fn(&Row) -> Option<u64>| match cheapest(&mine, budget, key) {
                Some(r) => format!(
                    "{} | {} | {:.4}",
                    r.label(),
                    key(r).unwrap_or(0),
                    r.misclassified_percent.unwrap_or(f64::NAN)
                ),
                None => "none meets it | – | –".to_owned(),
            };
            let _ = writeln!(s, "| {budget} % | {} | {} |", by(|r| r.total_cycles), by(|r| r.total_bytes));
        }
        let best = mine.iter().filter(|r| r.misclassified_percent.is_some()).min_by(|a, b| {
            a.misclassified_percent.partial_cmp(&b.misclassified_percent).unwrap_or(std::cmp::Ordering::Equal)
        });
        if let Some(b) = best {
            let _ = writeln!(
                s,
                "\nLowest error: {} at {:.4} %.",
                b.render_label(),
                b.misclassified_percent.unwrap_or(f64::NAN)
            );
        }
        if let Some(n) = mine.iter().find_map(|r| r.evaluated).filter(|&n| n > 0) {
            #[allow(clippy::cast_precision_loss, reason = "a pixel count")]
            let one = 100.0 / n as f64;
            let _ = writeln!(s, "{n} pixels evaluated: one pixel is {one:.4} %.");
        }
        let _ = writeln!(s);
    }
    if !skipped.is_empty() {
        let _ = writeln!(s, "## Skipped\n");
        let _ = writeln!(s, "| row | configuration | reason |");
        let _ = writeln!(s, "|---:|---|---|");
        for r in skipped {
            let _ = writeln!(s, "| {} | {} {} | {} |", r.index, r.scene, r.label(), r.reason.replace('|', "\\|"));
        }
    }
    s
}
