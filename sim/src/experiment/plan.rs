//! The planner: the least costly configuration a scene needs for an error
//! budget, modelling only what the scene requires.
//!
//! 1. **Buffers.** A scene of solids gets its second depth from one buffer
//!    by front-face culling (Wang & Molnar 1994 §3.4). Open surfaces cannot
//!    be front-face culled (they have no back), so a scene with any gets the
//!    dual unit and Weiskopf & Ertl's dual test with per-object culling.
//! 2. **Precision.** The dual map of the scene, rendered in the f32 format,
//!    gives the gap `z2 − z1` between the nearest and second-nearest surface
//!    at every texel where both exist; the tests place their reference
//!    inside that gap, so 16-bit depth suffices when the thinnest gaps (the
//!    1st percentile, ignoring grazing slivers at silhouettes) span at least
//!    [`GAP_LSBS`] 16-bit steps. This folds in the depth range: a large
//!    far/near ratio squeezes distant gaps into few steps.
//! 3. **Map size and filter.** Each candidate is rendered at a quarter of
//!    the scene's image (one reference ray per pixel) to predict its error
//!    and cost; the cheapest predicted to meet the budget is chosen, then
//!    rendered at full size against the 4×4-ray reference for the measured
//!    figures.

use indicatif::ProgressBar;
use serde::Serialize;
use umbra_core::shadow::Filter;
use umbra_core::{CullMode, DepthFormat, DepthFormatKind, DepthUnit, F32, LightPassConfig, RasterConfig};

use crate::cost::arch::{Arch, CostReport};
use crate::cost::storage::{MapShape, StorageBytes, storage_bytes};
use crate::experiment::presets::FILTERS;
use crate::io::limits::Limits;
use crate::pass::light::{self, DEFAULT_BIN_CAPACITY, LightFrame, LightOptions};
use crate::render::{Algorithm, Culling, Render, RenderConfig, RenderError, TruthSource, cost, render, truth};
use crate::truth::metrics::Metrics;
use crate::truth::reference::PixelTruth;
use crate::world::scene::Scene;

/// 16-bit steps the thinnest gaps between surfaces must span.
pub const GAP_LSBS: f64 = 8.0;

/// Tile side of the sparse storage scheme (Reeves et al. 1987 Table 2).
pub const STORAGE_TILE: u32 = 32;

/// The dual test's offset the planner uses, as a depth in `[0, 1]`.
pub const DUAL_OFFSET: f64 = 0.01;

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
    /// Camera image for the measurement (the prediction uses a quarter).
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
    /// Artifacts (acne and leaks away from the shadow boundary), percent
    /// of the evaluated pixels: what the budget bounds.
    pub artifact_percent: f64,
    /// Every misclassified pixel, edge placement included, percent.
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

/// A chosen configuration and why.
#[derive(Clone, Debug, Serialize)]
pub struct Plan {
    /// The configuration, at the measurement's image size.
    pub config: RenderConfig,
    /// Its filter.
    #[serde(with = "crate::base::text")]
    pub filter: Filter,
    /// Its depth format's name.
    pub format: String,
    /// The thinnest gap between surfaces (1st percentile), in 16-bit steps.
    pub gap_lsbs: f64,
    /// Whether the scene has open surfaces.
    pub open_surfaces: bool,
    /// Quarter-size prediction.
    pub predicted: Figures,
    /// Full-size measurement.
    pub measured: Figures,
    /// The same measured for the full configuration: the same test with
    /// the dual unit and 24-bit depth, the same map size and filter.
    pub full: Figures,
    /// Whether a candidate was predicted to meet the budget (else the most
    /// accurate one was taken).
    pub predicted_to_meet: bool,
    /// The reasons, one line each.
    pub reasons: Vec<String>,
    /// The chosen map's storage under Reeves et al.'s schemes (Table 2),
    /// tiles of [`STORAGE_TILE`].
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
pub fn thinnest_gap(scene: &Scene, map: u32) -> Result<f64, PlanError> {
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
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "cycles, rounded")]
    Figures {
        artifact_percent: m.artifact_percent,
        misclassified_percent: m.misclassified_percent,
        rms_error: m.rms_error,
        displacement: m.displacement[0],
        cycles: c.cycles.round() as u64,
        bytes: c.bytes,
    }
}

/// Error (against `truth`, the scene's reference at the configuration's
/// image and rays) and cost of `cfg` on `scene` under the spec's
/// architecture and within its limits, and the render.
fn evaluate(
    scene: &Scene,
    cfg: &RenderConfig,
    spec: &PlanSpec,
    truth: &[Option<PixelTruth>],
) -> Result<(Figures, Render), PlanError> {
    let r = render(scene, cfg, &spec.limits, TruthSource::Given(truth.to_vec()))?;
    let c = cost(scene, cfg, &spec.arch, &spec.limits)?;
    Ok((figures(&r.metrics, &c), r))
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
    let algorithm = if open_surfaces {
        let names: Vec<&str> = scene.objects.iter().filter(|o| !o.solid).map(|o| o.name.as_str()).collect();
        reasons.push(format!(
            "open surfaces ({}) have no back to cull: dual unit (z1, z2), Weiskopf & Ertl's dual test, solids back-face culled",
            names.join(", ")
        ));
        Algorithm::Dual { offset: DUAL_OFFSET }
    } else {
        reasons.push("every object is a closed solid: second depth by front-face culling, one depth buffer".into());
        Algorithm::SecondFrontCulled
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
            bias: 0.0,
            virtual_samples: true,
            width: image[0],
            height: image[1],
            reference_rays: rays,
            culling: Culling::ALGORITHM,
        }
    };
    let quarter = [(spec.image[0] / 2).max(1), (spec.image[1] / 2).max(1)];
    // The references, built once: candidates at a quarter of the image with
    // one ray per pixel, the plan and the full configuration at the image.
    let hidden = ProgressBar::hidden();
    let quarter_truth = truth(scene, quarter[0], quarter[1], 1, &hidden)?;
    let image_truth = truth(scene, spec.image[0], spec.image[1], 4, &hidden)?;
    let mut best: Option<(Figures, u32, Filter)> = None;
    let mut most_accurate: Option<(Figures, u32, Filter)> = None;
    for &map in &spec.map_sizes {
        for &filter in filters {
            let (f, _) = evaluate(scene, &at(quarter, map, filter, algorithm, format, 1), spec, &quarter_truth)?;
            if most_accurate.is_none_or(|(b, ..)| f.artifact_percent < b.artifact_percent) {
                most_accurate = Some((f, map, filter));
            }
            if f.artifact_percent <= spec.budget_percent
                && best.is_none_or(|(b, ..)| (f.cycles, f.bytes) < (b.cycles, b.bytes))
            {
                best = Some((f, map, filter));
            }
        }
    }
    let predicted_to_meet = best.is_some();
    let Some((predicted, map, filter)) = best.or(most_accurate) else {
        return Err(PlanError::Spec("no candidate".into()));
    };
    if predicted_to_meet {
        reasons.push(format!(
            "{map}² map with the {filter} filter: the cheapest candidate predicted under {}% ({} candidates at {}×{})",
            spec.budget_percent,
            spec.map_sizes.len() * filters.len(),
            quarter[0],
            quarter[1]
        ));
    } else {
        reasons.push(format!(
            "no candidate is predicted under {}%: the most accurate, {map}² with the {filter} filter",
            spec.budget_percent
        ));
    }
    let config = at(spec.image, map, filter, algorithm, format, 4);
    let (measured, r) = evaluate(scene, &config, spec, &image_truth)?;
    let raster = r.maps.maps.config.raster;
    let shape = MapShape::of_format(raster.width(), raster.height(), r.maps.format);
    let storage = storage_bytes(&shape, &r.maps.buffers(), STORAGE_TILE)
        .map_err(|e| PlanError::Spec(format!("map storage: {e}")))?;
    // The same test with everything: the dual unit's own z2 and 24 bits.
    let full_algorithm = if algorithm == Algorithm::SecondFrontCulled { Algorithm::Second } else { algorithm };
    let full_config = at(spec.image, map, filter, full_algorithm, DepthFormatKind::D24, 4);
    let (full, _) = evaluate(scene, &full_config, spec, &image_truth)?;
    Ok(Plan {
        config,
        filter,
        format: format!("{format:?}"),
        gap_lsbs,
        open_surfaces,
        predicted,
        measured,
        full,
        predicted_to_meet,
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
            "## Plan for `{}` (artifact budget {budget_percent}%)\n\n{}, {}, {}² map, {} filter\n\n`{}`\n",
            scene.name,
            c.algorithm.name(),
            c.format.name(),
            c.map_size,
            self.filter,
            c.command(&scene.source)
        );
        for r in &self.reasons {
            let _ = writeln!(s, "- {r}");
        }
        let _ = writeln!(
            s,
            "\n| | artifacts % | misclassified % | RMS area error | displacement (px) | cycles | DRAM bytes |\n|---|---:|---:|---:|---:|---:|---:|"
        );
        for (name, f) in [
            ("predicted (quarter image)", self.predicted),
            ("measured", self.measured),
            ("full: dual unit, 24-bit", self.full),
        ] {
            let _ = writeln!(
                s,
                "| {name} | {:.3} | {:.3} | {:.4} | {:.2} | {} | {} |",
                f.artifact_percent, f.misclassified_percent, f.rms_error, f.displacement, f.cycles, f.bytes
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
            "| {STORAGE_TILE}×{STORAGE_TILE} tiles | {} | {} of {} tiles that received geometry |",
            st.tiles, st.stored_tiles, st.grid_tiles
        );
        s
    }
}
