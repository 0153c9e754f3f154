//! The sweep: the algorithms and their parameters, the axes of a study, its configurations and shards.

use umbra_core::DepthFormatKind;
use umbra_core::shadow::{Filter, Jitter};

use super::StudyError;
use crate::cost::arch::Arch;
use crate::io::limits::Limits;
use crate::pass::render::{Algorithm, Culling};
use crate::world::scene::Scene;

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
        Self { name, algorithm, bias, virtual_samples: true, culling: Culling::ALGORITHM }
    }

    /// The same with virtual samples off.
    #[must_use]
    pub const fn without_virtual_samples(mut self) -> Self {
        self.virtual_samples = false;
        self
    }

    /// The same with nothing culled (the comparison Weiskopf & Ertl's
    /// Figures 5 and 6 make).
    #[must_use]
    pub const fn without_culling(mut self) -> Self {
        self.culling = Culling::OFF;
        self
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
    /// Architectures; none: metrics only, one row per configuration.
    pub archs: Vec<Arch>,
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
    /// 64 … 2048 texels, the five filters of [`crate::experiment::presets::FILTERS`],
    /// the three paper-era presets ([`Arch::era_presets`]), 320×180 images against 4×4 reference rays.
    #[must_use]
    pub fn full(scenes: Vec<Scene>) -> Self {
        Self {
            scenes,
            variants: algorithms(false),
            formats: vec![DepthFormatKind::D16, DepthFormatKind::D24, DepthFormatKind::F32],
            map_sizes: vec![64, 128, 256, 512, 1024, 2048],
            filters: crate::experiment::presets::FILTERS.iter().map(|(n, f)| ((*n).to_owned(), *f)).collect(),
            archs: Arch::era_presets(),
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
            filters: crate::experiment::presets::FILTERS
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
