//! The planner: the least costly configuration a scene needs for an error
//! budget, modelling only what the scene requires.
//!
//! 1. **Buffers.** A scene of solids gets second depth: from one buffer by
//!    front-face culling (Wang & Molnar 1994 §3.4), or from the dual unit's
//!    `z2`, whichever meets the budget more cheaply (culling the front faces
//!    is not always the cheaper: it draws the backs, which can shadow more
//!    and need more virtual samples). Open surfaces cannot be front-face
//!    culled (they have no back), so a scene with any gets the dual unit
//!    and Weiskopf & Ertl's dual test with per-object culling.
//! 2. **Precision.** The dual map of the scene, rendered in the f32 format,
//!    gives the gap `z2 − z1` between the nearest and second-nearest surface
//!    at every texel where both exist; the tests place their reference
//!    inside that gap, so 16-bit depth suffices when the thinnest gaps (the
//!    1st percentile, ignoring grazing slivers at silhouettes) span at least
//!    `GAP_LSBS` 16-bit steps. This folds in the depth range: a large
//!    far/near ratio squeezes distant gaps into few steps.
//! 3. **Algorithm, map size and filter.** Every candidate (for solids,
//!    second depth by front-face culling or from the dual unit; × map side
//!    × filter) is
//!    costed on the architecture at the scene's image, and the candidates
//!    are measured against the 4×4-ray reference cheapest first (cycles,
//!    then DRAM bytes) until one meets the budget: the first that does is
//!    the cheapest that does. Only when every candidate has been measured
//!    and missed is the most accurate taken, and the plan says so.

use indicatif::ProgressBar;
use serde::Serialize;
use umbra_core::shadow::Filter;
use umbra_core::{CullMode, DepthFormat, DepthFormatKind, DepthUnit, F32, LightPassConfig, RasterConfig};

use crate::cost::arch::Arch;
use crate::cost::report::CostReport;
use crate::cost::report::stats::whole_cycles;
use crate::cost::storage::{MapShape, REEVES_TILE, StorageBytes, storage_bytes};
use crate::experiment::presets::FILTERS;
use crate::input::limits::Limits;
use crate::pass::light::{self, DEFAULT_BIN_CAPACITY, LightFrame, LightOptions};
use crate::render::{Algorithm, Render, RenderConfig, RenderError, TruthSource, cost, render, truth};
use crate::truth::metrics::Metrics;
use crate::truth::reference::PixelTruth;
use crate::world::scene::Scene;

/// 16-bit steps the thinnest gaps between surfaces must span.
pub(crate) const GAP_LSBS: f64 = 8.0;

/// The dual test's offset the planner uses, as a depth in `[0, 1]`.
pub(crate) const DUAL_OFFSET: f64 = 0.01;

/// What the planner may choose from.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanSpec {
    /// Misclassified pixels allowed, percent of those facing the light.
    pub budget_percent: f64,
    /// Map sides to try, ascending.
    pub map_sizes: Vec<u32>,
    /// Filters to try.
    pub filters: Vec<Filter>,
    /// The architecture whose cost is minimised.
    pub arch: Arch,
    /// Camera image the candidates are measured at.
    pub image: [u32; 2],
    /// What each render may ask for.
    pub limits: Limits,
}

impl PlanSpec {
    /// Map sizes 128…2048, point, bilinear and 3×3 box filters, the
    /// Talisman preset, the scene's own image.
    #[must_use]
    pub fn new(scene: &Scene, budget_percent: f64) -> Self {
        Self {
            budget_percent,
            map_sizes: vec![128, 256, 512, 1024, 2048],
            filters: FILTERS[..3].to_vec(),
            arch: Arch::bundled("talisman").unwrap_or_default(),
            image: scene.image,
            limits: Limits::DEFAULT,
        }
    }
}

/// Error and cost of one configuration.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Figures {
    /// Artifacts (acne, detachment and leaks, by their cause), percent
    /// of the evaluated pixels: what the budget bounds.
    pub artifact_percent: f64,
    /// Every misclassified pixel, aliasing included, percent.
    pub misclassified_percent: f64,
    /// RMS area error.
    pub rms_error: f64,
    /// Mean boundary displacement, pixels.
    pub displacement: f64,
    /// Light plus camera bottleneck cycles.
    pub cycles: u64,
    /// DRAM bytes of both passes.
    pub bytes: u64,
}

/// One candidate as the planner measured it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Candidate {
    /// Its algorithm, as `--algo` spells it.
    pub algorithm: String,
    /// Map side, texels.
    pub map_size: u32,
    /// Filter.
    #[serde(with = "crate::base::text")]
    pub filter: Filter,
    /// Its figures at the image.
    pub figures: Figures,
}

/// A chosen configuration and why.
#[derive(Clone, Debug, Serialize)]
pub struct Plan {
    /// The configuration, at the measurement's image size.
    pub config: RenderConfig,
    /// Its algorithm, as `umbra render --algo` spells it.
    pub algorithm: String,
    /// Its filter.
    #[serde(with = "crate::base::text")]
    pub filter: Filter,
    /// Its depth format's name.
    pub format: String,
    /// The architecture whose cost was minimised.
    pub arch: String,
    /// The `umbra render` command that renders the plan.
    pub command: String,
    /// The thinnest gap between surfaces (1st percentile), in 16-bit steps.
    pub gap_lsbs: f64,
    /// Whether the scene has open surfaces.
    pub open_surfaces: bool,
    /// The chosen candidate's measurement.
    pub measured: Figures,
    /// The same measured for the full configuration: the same test with
    /// the dual unit and 24-bit depth, the same map size and filter.
    pub full: Figures,
    /// How many candidates there were.
    pub candidates: usize,
    /// The candidates measured, cheapest first, up to the one chosen (all
    /// of them when none meets the budget).
    pub tried: Vec<Candidate>,
    /// The reasons, one line each.
    pub reasons: Vec<String>,
    /// The chosen map's storage under Reeves et al.'s schemes (Table 2),
    /// tiles of `REEVES_TILE`.
    pub storage: StorageBytes,
}

impl Plan {
    /// Whether the measured artifacts meet the budget.
    #[must_use]
    pub fn meets(&self, budget_percent: f64) -> bool {
        self.measured.artifact_percent <= budget_percent
    }
}

/// Why planning failed.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// A render failed.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The spec names no map size or filter, or an unknown filter.
    #[error("plan: {0}")]
    Spec(String),
}

/// The thinnest gaps between the nearest and second-nearest surface, in
/// 16-bit steps: the 1st percentile over texels where both exist.
///
/// # Errors
/// [`PlanError::Render`] when the light pass cannot run.
pub(crate) fn thinnest_gap(scene: &Scene, map: u32) -> Result<f64, PlanError> {
    let raster = RasterConfig::new(map, map, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
        .map_err(RenderError::MapSize)?;
    let config = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let draws = scene.draws(scene.light().view_projection(), CullMode::None);
    let mut frame = LightFrame::new();
    let (maps, _) = light::render::<F32, _, DEFAULT_BIN_CAPACITY>(
        &mut frame,
        config,
        &draws,
        LightOptions::default(),
        umbra_core::NoProbe,
    )
    .map_err(RenderError::from)?;
    let far = F32::FAR;
    let mut gaps: Vec<f64> = maps
        .z1
        .iter()
        .zip(&maps.z2)
        .filter(|&(&a, &b)| a != far && b != far)
        .map(|(&a, &b)| (F32::unquantize(b) - F32::unquantize(a)) * 65_535.0)
        .collect();
    if gaps.is_empty() {
        return Ok(f64::INFINITY);
    }
    gaps.sort_by(f64::total_cmp);
    Ok(gaps[gaps.len() / 100])
}

fn figures(m: &Metrics, c: &CostReport) -> Figures {
    Figures {
        artifact_percent: m.artifact_percent,
        misclassified_percent: m.misclassified_percent,
        rms_error: m.rms_error,
        displacement: m.displacement[0],
        cycles: whole_cycles(c.cycles),
        bytes: c.bytes,
    }
}

/// Error of `cfg` on `scene` against `truth` (the scene's reference at the
/// configuration's image and rays), with its cost `c`, and the render.
fn measure(
    scene: &Scene,
    cfg: &RenderConfig,
    spec: &PlanSpec,
    truth: &[Option<PixelTruth>],
    c: &CostReport,
) -> Result<(Figures, Render), PlanError> {
    let r = render(&cfg.check(scene, &spec.limits)?, TruthSource::Given(truth.to_vec()))?;
    Ok((figures(&r.metrics, c), r))
}

/// Plan `scene` within `spec`.
///
/// ```
/// use umbra_core::shadow::Filter;
/// use umbra_sim::{Limits, PlanSpec, Scene};
/// let scene = Scene::open("weiskopf-l", &Limits::DEFAULT)?;
/// let spec = PlanSpec {
///     map_sizes: vec![128, 256],
///     filters: vec![Filter::Point, Filter::Bilinear],
///     image: [96, 72],
///     ..PlanSpec::new(&scene, 1.0)
/// };
/// let plan = umbra_sim::plan(&scene, &spec)?;
/// assert!(spec.map_sizes.contains(&plan.config.map_size));
/// assert!(plan.config.command(&scene.source).starts_with("umbra render weiskopf-l"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// See [`PlanError`].
pub fn plan(scene: &Scene, spec: &PlanSpec) -> Result<Plan, PlanError> {
    let filters = &spec.filters;
    if spec.map_sizes.is_empty() || filters.is_empty() {
        return Err(PlanError::Spec("no map size or no filter to choose from".into()));
    }
    let mut reasons = Vec::new();
    let open_surfaces = scene.objects.iter().any(|o| !o.solid);
    let algorithms = if open_surfaces {
        let names: Vec<&str> = scene.objects.iter().filter(|o| !o.solid).map(|o| o.name.as_str()).collect();
        reasons.push(format!(
            "open surfaces ({}) have no back to cull: dual unit (z1, z2), Weiskopf & Ertl's dual test, solids back-face culled",
            names.join(", ")
        ));
        vec![Algorithm::Dual { offset: DUAL_OFFSET }]
    } else {
        reasons.push(
            "every object is a closed solid: second depth, by front-face culling into one depth buffer or from the dual unit's z2, whichever meets the budget more cheaply"
                .into(),
        );
        vec![Algorithm::SecondFrontCulled, Algorithm::Second]
    };
    let gap_map = spec.map_sizes.iter().copied().max().unwrap_or(512).min(1024);
    let gap_lsbs = thinnest_gap(scene, gap_map)?;
    let format = if gap_lsbs >= GAP_LSBS {
        reasons.push(format!(
            "thinnest gaps between surfaces span {gap_lsbs:.0} 16-bit steps (1st percentile, {gap_map}² f32 map) ≥ {GAP_LSBS}: 16-bit depth"
        ));
        DepthFormatKind::D16
    } else {
        reasons.push(format!(
            "thinnest gaps between surfaces span only {gap_lsbs:.1} 16-bit steps (1st percentile, {gap_map}² f32 map) < {GAP_LSBS}: 24-bit depth"
        ));
        DepthFormatKind::D24
    };
    let at = |image: [u32; 2], map: u32, filter: Filter, algorithm: Algorithm, format: DepthFormatKind, rays: u32| {
        RenderConfig {
            algorithm,
            format,
            map_size: map,
            filter,
            width: image[0],
            height: image[1],
            reference_rays: rays,
            ..RenderConfig::DEFAULT
        }
    };
    // Every candidate costed at the image, cheapest first; then measured
    // in that order until one meets the budget.
    let image_truth = truth(scene, spec.image[0], spec.image[1], 4, &ProgressBar::hidden())?;
    let mut costed = Vec::new();
    for &algorithm in &algorithms {
        for &map in &spec.map_sizes {
            for &filter in filters {
                let cfg = at(spec.image, map, filter, algorithm, format, 4);
                let c = cost(&cfg.check(scene, &spec.limits)?, &spec.arch)?;
                costed.push((cfg, c));
            }
        }
    }
    costed.sort_by(|(_, a), (_, b)| a.cycles.total_cmp(&b.cycles).then(a.bytes.cmp(&b.bytes)));
    let mut tried = Vec::new();
    let mut chosen: Option<(Figures, Render, RenderConfig)> = None;
    let mut most_accurate: Option<(Figures, Render, RenderConfig)> = None;
    for (cfg, c) in &costed {
        let (f, r) = measure(scene, cfg, spec, &image_truth, c)?;
        tried.push(Candidate {
            algorithm: cfg.algorithm.name().to_owned(),
            map_size: cfg.map_size,
            filter: cfg.filter,
            figures: f,
        });
        if f.artifact_percent <= spec.budget_percent {
            chosen = Some((f, r, *cfg));
            break;
        }
        if most_accurate.as_ref().is_none_or(|(b, ..)| f.artifact_percent < b.artifact_percent) {
            most_accurate = Some((f, r, *cfg));
        }
    }
    let n = costed.len();
    let meets = chosen.is_some();
    let Some((measured, r, config)) = chosen.or(most_accurate) else {
        return Err(PlanError::Spec("no candidate".into()));
    };
    let (map, filter) = (config.map_size, config.filter);
    if meets {
        reasons.push(format!(
            "{}, {map}² map with the {filter} filter: the cheapest of {n} candidates (algorithms × map sides × filters) to meet {}% on {}, {} of them measured cheapest first",
            config.algorithm.name(),
            spec.budget_percent,
            spec.arch.name,
            tried.len()
        ));
    } else {
        reasons.push(format!(
            "no candidate meets {}%: all {n} measured; the most accurate, {}, {map}² with the {filter} filter",
            spec.budget_percent,
            config.algorithm.name()
        ));
    }
    let raster = r.maps.maps.config.raster;
    let shape = MapShape::of_format(raster.width(), raster.height(), r.maps.format);
    let storage = storage_bytes(&shape, &r.maps.buffers(), REEVES_TILE)
        .map_err(|e| PlanError::Spec(format!("map storage: {e}")))?;
    // The same test with everything: the dual unit's own z2 and 24 bits.
    let full_algorithm =
        if config.algorithm == Algorithm::SecondFrontCulled { Algorithm::Second } else { config.algorithm };
    let full_config = at(spec.image, map, filter, full_algorithm, DepthFormatKind::D24, 4);
    let full_cost = cost(&full_config.check(scene, &spec.limits)?, &spec.arch)?;
    let (full, _) = measure(scene, &full_config, spec, &image_truth, &full_cost)?;
    Ok(Plan {
        config,
        algorithm: config.algorithm.name().to_owned(),
        filter,
        format: format.name().to_owned(),
        arch: spec.arch.name.clone(),
        command: config.command(&scene.source),
        gap_lsbs,
        open_surfaces,
        measured,
        full,
        candidates: n,
        tried,
        reasons,
        storage,
    })
}

impl Plan {
    /// The plan as Markdown: the choices, why, and the figures.
    #[must_use]
    pub fn markdown(&self, scene: &Scene, budget_percent: f64) -> String {
        use std::fmt::Write as _;
        let mut s = String::new();
        let c = &self.config;
        let _ = writeln!(
            s,
            "## Plan for `{}` (artifact budget {budget_percent}%, costed on `{}`)\n\n{}, {}, {}² map, {} filter\n\n`{}`\n",
            scene.name, self.arch, self.algorithm, self.format, c.map_size, self.filter, self.command
        );
        for r in &self.reasons {
            let _ = writeln!(s, "- {r}");
        }
        let _ = writeln!(
            s,
            "\n| | artifacts % | misclassified % | RMS area error | displacement (px) | cycles | DRAM bytes |\n|---|---:|---:|---:|---:|---:|---:|"
        );
        for (name, f) in [("measured", self.measured), ("full: dual unit, 24-bit", self.full)] {
            let _ = writeln!(
                s,
                "| {name} | {:.3} | {:.3} | {:.4} | {:.2} | {} | {} |",
                f.artifact_percent, f.misclassified_percent, f.rms_error, f.displacement, f.cycles, f.bytes
            );
        }
        let _ = writeln!(
            s,
            "\nCandidates measured, cheapest first ({} of {}):\n\n| algorithm | map | filter | artifacts % | cycles | DRAM bytes |\n|---|---:|---|---:|---:|---:|",
            self.tried.len(),
            self.candidates
        );
        for t in &self.tried {
            let f = t.figures;
            let _ = writeln!(
                s,
                "| {} | {} | {} | {:.3} | {} | {} |",
                t.algorithm, t.map_size, t.filter, f.artifact_percent, f.cycles, f.bytes
            );
        }
        let st = &self.storage;
        let _ = writeln!(
            s,
            "\nMap storage (Reeves et al. Table 2), {} buffer(s):\n\n| scheme | bytes | holds |\n|---|---:|---|",
            st.buffers
        );
        let _ = writeln!(s, "| raw | {} | every texel |", st.raw);
        let _ = writeln!(s, "| bounding box | {} | {} texels of finite depth |", st.bounding_box, st.box_texels);
        let _ = writeln!(
            s,
            "| {REEVES_TILE}×{REEVES_TILE} tiles | {} | {} of {} tiles that received geometry |",
            st.tiles, st.stored_tiles, st.grid_tiles
        );
        s
    }
}
