//! The sweep: the algorithms and their parameters, the axes of a study, its configurations and shards.

use umbra_core::DepthFormatKind;
use umbra_core::shadow::Filter;

use super::StudyError;
use crate::cost::arch::Arch;
use crate::input::limits::{Footprint, LimitError, Limits};
use crate::render::{Algorithm, Culling};
use crate::world::cascade::Cascades;
use crate::world::scene::Scene;

/// One point on the study's algorithm axis: a shadow algorithm with its
/// bias, virtual samples and culling.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// The algorithm.
    pub algorithm: Algorithm,
    /// The bias, as a depth in `[0, 1]`.
    pub bias: f64,
    /// Wang & Molnar's virtual samples (second depth only).
    pub virtual_samples: bool,
    /// The light pass's culling.
    pub culling: Culling,
    /// Every directional light's cascades (`None`: each light's own, as
    /// its scene gives them).
    pub cascades: Option<Cascades>,
}

impl Variant {
    /// An algorithm at a bias, virtual samples on, the algorithm's own culling.
    #[must_use]
    pub const fn new(algorithm: Algorithm, bias: f64) -> Self {
        Self { algorithm, bias, virtual_samples: true, culling: Culling::ALGORITHM, cascades: None }
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

    /// The same drawn through `cascades` for every directional light.
    #[must_use]
    pub const fn with_cascades(mut self, cascades: Cascades) -> Self {
        self.cascades = Some(cascades);
        self
    }
}

#[cfg(test)]
/// Reeves' jittered filter with `n` samples per lookup, his other Figure 4
/// parameters unchanged.
#[must_use]
pub(crate) fn jittered(n: u16) -> Filter {
    Filter::Jittered(umbra_core::shadow::Jitter { num_samples: n, ..umbra_core::shadow::Jitter::REEVES })
}

/// Most configurations a sweep may have.
pub const MAX_CONFIGURATIONS: usize = 1 << 20;
/// Most architecture points a sweep may cost each configuration on.
pub const MAX_ARCHITECTURES: usize = 1024;

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
    pub filters: Vec<Filter>,
    /// Architectures; none: metrics only, one row per configuration.
    pub archs: Vec<Arch>,
    /// Each architecture's base and parameter-axis assignments (missing
    /// for an architecture without axes).
    pub arch_points: Vec<ArchPoint>,
    /// Camera image sizes, width × height: an axis, so that the summary
    /// can say where a winner changes with the image.
    pub images: Vec<[u32; 2]>,
    /// Reference rays per pixel side.
    pub reference_rays: u32,
    /// The summary's error budgets, each on a measure of the metrics.
    pub budgets: Vec<crate::experiment::study::budget::Budget>,
    /// The most the summary's best per objective may cost.
    pub cost_limits: super::objective::CostLimits,
    /// The sweep's name (`quick`, `full`, or the file's).
    pub name: String,
    /// The hash of the sweep file's text (`crate::output::provenance::hash`),
    /// which every row and manifest carries.
    pub hash: String,
    /// What each render may ask for: a configuration beyond them is a
    /// skipped row that says which limit.
    pub limits: Limits,
}

impl Spec {
    /// The bundled quick sweep (`sweeps/quick.toml`) over `scenes`.
    ///
    /// # Panics
    /// Never: the bundled sweep files are validated by the tests.
    #[must_use]
    pub fn quick(scenes: Vec<Scene>) -> Self {
        Self { scenes, ..super::SweepFile::bundled("quick").and_then(|f| f.spec(&Limits::DEFAULT)).expect("valid") }
    }

    /// Why the sweep is too large to run, if it is: more than
    /// [`MAX_CONFIGURATIONS`] configurations or [`MAX_ARCHITECTURES`]
    /// architecture points (each a loop over the input, bounded here).
    #[must_use]
    pub(crate) fn size_problem(&self) -> Option<String> {
        let axes = [
            self.scenes.len(),
            self.images.len(),
            self.variants.len(),
            self.formats.len(),
            self.map_sizes.len(),
            self.filters.len(),
        ];
        let configs = axes.iter().try_fold(1usize, |n, &k| n.checked_mul(k));
        if configs.is_none_or(|n| n > MAX_CONFIGURATIONS) {
            let n = configs.map_or_else(|| "more than can be counted".to_owned(), |n| n.to_string());
            return Some(format!("{n} configurations; at most {MAX_CONFIGURATIONS}"));
        }
        if self.archs.len() > MAX_ARCHITECTURES {
            return Some(format!("{} architecture points; at most {MAX_ARCHITECTURES}", self.archs.len()));
        }
        None
    }

    /// How many configurations may render at once on `threads` threads
    /// within [`Limits::max_memory`]: every scene is held, with one
    /// reference at the largest image, and each render takes
    /// [`Footprint::render`] of the largest image and map within the limits
    /// (larger ones are skipped rows that build nothing).
    ///
    /// # Errors
    /// [`LimitError::Memory`] when not even one render fits.
    pub(crate) fn renders_at_once(&self, threads: usize) -> Result<usize, LimitError> {
        self.memory(threads).map(|(n, _)| n)
    }

    /// The renders `Spec::renders_at_once` allows and the memory the
    /// study is then bounded by, bytes: its scenes, one reference, what
    /// configurations share, and that many renders (an upper bound: see
    /// [`Footprint`] for its margin over the peak measured).
    ///
    /// # Errors
    /// [`LimitError::Memory`] when not even one render fits.
    pub fn memory(&self, threads: usize) -> Result<(usize, u64), LimitError> {
        let pixels = self
            .images
            .iter()
            .filter(|&&[w, h]| self.limits.check_image(w, h).is_ok())
            .map(|&[w, h]| u64::from(w) * u64::from(h))
            .max()
            .unwrap_or(0);
        let map = self.map_sizes.iter().copied().filter(|&m| self.limits.check_map(m).is_ok()).max().unwrap_or(0);
        let triangles = |s: &Scene| s.objects.iter().map(|o| o.mesh.triangles.len() as u64).sum::<u64>();
        let held = self.scenes.iter().map(triangles).fold(0u64, u64::saturating_add);
        let most = self.scenes.iter().map(triangles).max().unwrap_or(0);
        let lights = self.scenes.iter().map(|s| (s.lights.len() + s.shadowless.len()) as u64).max().unwrap_or(1);
        let reference = Footprint::render_lit(pixels, 0, most, lights) - Footprint::BASE;
        let render = Footprint::render_lit(pixels, map, most, lights) - Footprint::BASE;
        // What the configurations of a scene and image share: its
        // visibility in each tiling, and a block's light passes (one a
        // point on the algorithm axis at most).
        let tilings = crate::render::shared::tilings(&self.archs) as u64;
        let texels = u64::from(map) * u64::from(map);
        let casting = self.scenes.iter().map(|s| s.lights.len().max(1) as u64).max().unwrap_or(1);
        let shares = crate::render::shared::image_bytes(pixels, tilings, (most, casting)).saturating_add(
            crate::render::shared::light_bytes(texels, tilings, casting).saturating_mul(self.variants.len() as u64),
        );
        // A scene of several lights is held once more for each light, as
        // that light alone lights it.
        let lit =
            if casting > 1 { (Footprint::render(0, 0, most) - Footprint::BASE).saturating_mul(casting) } else { 0 };
        let fixed = Footprint::render(0, 0, held).saturating_add(reference).saturating_add(shares).saturating_add(lit);
        let room = self.limits.max_memory.saturating_sub(fixed) / render.max(1);
        if room == 0 {
            self.limits
                .check_memory("the study (its scenes, one reference and one render)", fixed.saturating_add(render))?;
        }
        let n = usize::try_from(room).unwrap_or(usize::MAX).clamp(1, threads.max(1));
        Ok((n, fixed.saturating_add(render.saturating_mul(n as u64))))
    }

    /// Every configuration, in the fixed order that numbers them: scene,
    /// image size, algorithm, format, map size, filter.
    #[must_use]
    pub fn configs(&self) -> Vec<Config> {
        let mut out = Vec::new();
        for scene in 0..self.scenes.len() {
            for image in 0..self.images.len() {
                for variant in 0..self.variants.len() {
                    for &format in &self.formats {
                        for &map_size in &self.map_sizes {
                            for filter in 0..self.filters.len() {
                                out.push(Config { index: out.len(), scene, image, variant, format, map_size, filter });
                            }
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
    /// Image size.
    pub image: usize,
    /// Algorithm.
    pub variant: usize,
    /// Depth format.
    pub format: DepthFormatKind,
    /// Map side.
    pub map_size: u32,
    /// Filter.
    pub filter: usize,
}

/// How a sweep's configurations fall into blocks that share their passes:
/// a block is every configuration of one scene, image size, depth format
/// and map side (every algorithm and filter of them), so it draws the
/// scene's visibility and each light pass once. Only the axis lengths
/// matter, so a merge can check a shard's rows from its manifest alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Layout {
    /// Configurations in the sweep.
    pub configurations: usize,
    /// Points on the algorithm axis.
    pub variants: usize,
    /// Depth formats.
    pub formats: usize,
    /// Map sides.
    pub maps: usize,
    /// Filters.
    pub filters: usize,
}

impl Layout {
    /// The layout of `spec`'s configurations ([`Spec::configs`]).
    #[must_use]
    pub(crate) fn of(spec: &Spec) -> Self {
        let configurations = spec.configs().len();
        let (variants, formats, maps, filters) =
            (spec.variants.len(), spec.formats.len(), spec.map_sizes.len(), spec.filters.len());
        Self { configurations, variants, formats, maps, filters }
    }

    /// Configurations a block holds: every algorithm and filter.
    #[must_use]
    pub(crate) const fn block_size(&self) -> usize {
        self.variants.saturating_mul(self.filters)
    }

    /// Blocks in the sweep.
    #[must_use]
    pub(crate) const fn blocks(&self) -> usize {
        match self.configurations.checked_div(self.block_size()) {
            Some(b) => b,
            None => 0,
        }
    }

    /// The block of configuration `index`, and its place in the block
    /// (algorithm-major, as [`Spec::configs`] numbers them).
    #[must_use]
    pub(crate) fn block_of(&self, index: usize) -> (usize, usize) {
        let axis = |n: usize, of: usize| if of == 0 { (0, 0) } else { (n % of, n / of) };
        let (filter, rest) = axis(index, self.filters);
        let (map, rest) = axis(rest, self.maps);
        let (format, rest) = axis(rest, self.formats);
        let (variant, scene_image) = axis(rest, self.variants);
        ((scene_image * self.formats + format) * self.maps + map, variant * self.filters + filter)
    }
}

/// A deterministic partition of the configurations into `count` shards
/// that keep blocks whole ([`Layout`]): with no more shards than blocks,
/// shard `index` runs the blocks whose number is `index` modulo `count`
/// (so every shard mixes scenes, formats and map sides as the sweep does);
/// with more, each block is cut into as many equal runs as it takes to
/// give every shard work, and the runs are dealt the same way.
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
    pub(crate) fn parse(s: &str) -> Result<Self, StudyError> {
        let bad = || StudyError::Shard(s.to_owned());
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count) = (i.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// Whether this shard runs configuration `index` of a sweep laid out
    /// as `layout`.
    ///
    /// ```
    /// use umbra_sim::experiment::study::{Layout, Shard};
    /// // 2 scenes × 2 formats × 1 map side: 4 blocks of 3 algorithms × 2 filters.
    /// let layout = Layout { configurations: 24, variants: 3, formats: 2, maps: 1, filters: 2 };
    /// let shard = |i, n, c| Shard { index: i, count: n }.contains(&layout, c);
    /// // Two shards: blocks 0 and 2 in the first, 1 and 3 in the second.
    /// assert!(shard(0, 2, 0) && shard(0, 2, 5) && shard(1, 2, 2) && shard(0, 2, 12));
    /// // Eight shards: each block cut in two runs of 3 configurations.
    /// let mine: Vec<usize> = (0..24).filter(|&c| shard(0, 8, c)).collect();
    /// assert_eq!(mine.len(), 3);
    /// ```
    #[must_use]
    pub fn contains(self, layout: &Layout, index: usize) -> bool {
        let (block, at) = layout.block_of(index);
        let blocks = layout.blocks();
        let size = layout.block_size();
        // Runs a block is cut into: enough for every shard to have one.
        let runs = if blocks == 0 || size == 0 { 1 } else { self.count.div_ceil(blocks) };
        let runs = if runs > size { size } else { runs };
        let run = (at * runs).checked_div(size).unwrap_or(0);
        (block * runs + run) % self.count == self.index
    }
}

/// An architecture point of a sweep: the architecture it was made from and
/// the axis values assigned to it, as the sweep file spells them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ArchPoint {
    /// The base architecture's name.
    pub base: String,
    /// `(key, value)` per architecture axis, in the file's order.
    pub assignments: Vec<(String, String)>,
}

impl ArchPoint {
    /// The assignments as `key=value,…` (empty for none).
    #[must_use]
    pub fn params(&self) -> String {
        self.assignments.iter().map(|(k, v)| format!("{k}={v}")).collect::<Vec<_>>().join(",")
    }
}
