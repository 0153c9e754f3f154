//! The planner: the least costly configuration of a study's whole space
//! that meets every error budget a user sets on a scene.
//!
//! The space is a sweep's ([`PlanSpec::new`] takes the bundled quick
//! sweep's algorithms — first depth at its biases, Reeves' bias range,
//! second depth with and without virtual samples and by front-face
//! culling, the midpoint, dual depth at its offsets, silhouette maps,
//! shadow volumes — and its depth formats, over map sides 128 to 2048 and
//! the point, bilinear and 3×3 box filters; [`PlanSpec::from_sweep`] takes
//! a sweep file's). Every candidate is rendered, measured against the
//! exact reference and costed on the architecture by the study's own run
//! (which shares each light pass among the candidates that draw it), so
//! the pick is the cheapest *measured* candidate — in cycles on the
//! architecture, then DRAM bytes — whose every budgeted error class is
//! within its budget ([`Budget`]: artifacts, misclassified pixels, or any
//! single class of the metrics, judged by its cause). The plan lists the
//! runners-up: the cheaper candidates nearest it, each with the budgets it
//! missed, and the next dearer ones that meet every budget, with how much
//! dearer. When none meets every budget it takes the one nearest to doing
//! so (the least worst ratio of measure to budget) and says so.
//!
//! The thinnest gap between the nearest and second-nearest surfaces, in
//! 16-bit steps, is reported beside the pick: the tests place their
//! reference inside that gap, so it tells whether 16-bit depth can hold
//! the scene (`GAP_LSBS` steps).

use indicatif::ProgressBar;
use serde::Serialize;
use umbra_core::shadow::Filter;
use umbra_core::{CullMode, DepthFormat, DepthFormatKind, DepthUnit, F32, LightPassConfig, RasterConfig};

mod candidate;
mod report;
mod why;

pub use crate::experiment::study::budget::{Budget, Measure};
pub use crate::experiment::study::objective::{CostLimits, Costs, Objective};
pub use candidate::{Candidate, RunnerUp};

use crate::cost::arch::Arch;
use crate::cost::storage::{MapShape, REEVES_TILE, StorageBytes, storage_bytes};
use crate::experiment::presets::FILTERS;
use crate::experiment::study::{Row, Shard, Spec, StudyError, SweepFile, Variant, render_config, run};
use crate::input::limits::Limits;
use crate::pass::light::{self, DEFAULT_BIN_CAPACITY, LightFrame, LightOptions};
use crate::render::{RenderConfig, RenderError, TruthSource, render};
use crate::world::scene::Scene;

/// 16-bit steps the thinnest gaps between surfaces must span.
pub(crate) const GAP_LSBS: f64 = 8.0;

/// Reference rays per pixel side the candidates are measured against.
pub const REFERENCE_RAYS: u32 = 4;

/// The budgets a plan meets when none is given: artifacts within 0.1 %
/// and misclassified pixels within 2 % of the evaluated pixels — so a
/// render with few artifacts but most of its pixels wrong (a map too
/// coarse, say) is never the pick.
pub const DEFAULT_BUDGETS: [Budget; 2] =
    [Budget { measure: Measure::Artifacts, percent: 0.1 }, Budget { measure: Measure::Misclassified, percent: 2.0 }];

/// The cascades the planner's space adds for a scene lit by a directional
/// light: four, split by the practical scheme (Zhang et al. 2006).
pub const CASCADES: usize = 4;

/// `variants`, and for a scene with a directional light each that draws a
/// map again through [`CASCADES`] cascades: a view that needs them (the
/// camera among what the light covers, near and far) finds them cheaper
/// than one map large enough; one that does not finds one map cheaper.
fn with_cascades(scene: &Scene, variants: Vec<Variant>) -> Vec<Variant> {
    let directional = scene.lights.iter().any(|l| matches!(l, crate::world::scene::Light::Directional(..)));
    let Ok(cascades) = crate::world::cascade::Cascades::practical(CASCADES) else { return variants };
    if !directional {
        return variants;
    }
    let cascaded: Vec<Variant> = variants
        .iter()
        .filter(|v| v.algorithm != crate::render::Algorithm::Volumes)
        .map(|v| v.clone().with_cascades(cascades))
        .collect();
    variants.into_iter().chain(cascaded).collect()
}

/// What the planner may choose from, and the budgets it must meet.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanSpec {
    /// Every budget the pick must meet (at least one; each measure once).
    pub budgets: Vec<Budget>,
    /// Algorithm variants (algorithm, bias, virtual samples, culling).
    pub variants: Vec<Variant>,
    /// Depth formats.
    pub formats: Vec<DepthFormatKind>,
    /// Map sides.
    pub map_sizes: Vec<u32>,
    /// Filters.
    pub filters: Vec<Filter>,
    /// The architecture the candidates are costed on.
    pub arch: Arch,
    /// What the pick minimises.
    pub objective: Objective,
    /// The most the pick may cost.
    pub cost_limits: CostLimits,
    /// Camera image the candidates are measured at.
    pub image: [u32; 2],
    /// What each render may ask for.
    pub limits: Limits,
}

impl PlanSpec {
    /// The quick sweep's algorithms and depth formats, map sides 128 to
    /// 2048, the point, bilinear and 3×3 box filters, Talisman, the
    /// scene's own image. A scene lit by a directional light gets each
    /// algorithm that draws a map twice: through one map a light, and
    /// through [`CASCADES`] cascades of the map's side each.
    ///
    /// # Panics
    /// Never: the bundled sweep files are validated by the tests.
    #[must_use]
    pub fn new(scene: &Scene, budgets: Vec<Budget>) -> Self {
        let quick = SweepFile::bundled("quick").and_then(|f| f.spec(&Limits::DEFAULT)).expect("the bundled sweep");
        Self {
            budgets,
            variants: with_cascades(scene, quick.variants),
            formats: quick.formats,
            map_sizes: vec![128, 256, 512, 1024, 2048],
            filters: FILTERS[..3].to_vec(),
            arch: Arch::bundled("talisman").unwrap_or_default(),
            objective: Objective::Cycles,
            cost_limits: CostLimits::default(),
            image: scene.image,
            limits: Limits::DEFAULT,
        }
    }

    /// The space of a sweep: its algorithms, formats, map sides and
    /// filters (its scenes, images and architectures are not the plan's).
    #[must_use]
    pub fn from_sweep(scene: &Scene, budgets: Vec<Budget>, sweep: &Spec) -> Self {
        Self {
            variants: sweep.variants.clone(),
            formats: sweep.formats.clone(),
            map_sizes: sweep.map_sizes.clone(),
            filters: sweep.filters.clone(),
            ..Self::new(scene, budgets)
        }
    }

    /// How many candidates the space holds.
    #[must_use]
    pub fn candidates(&self) -> usize {
        self.variants.len() * self.formats.len() * self.map_sizes.len() * self.filters.len()
    }

    /// The study that measures every candidate on `scene`.
    fn study(&self, scene: &Scene) -> Spec {
        let name = format!("plan of {}", scene.name);
        Spec {
            scenes: vec![scene.clone()],
            variants: self.variants.clone(),
            formats: self.formats.clone(),
            map_sizes: self.map_sizes.clone(),
            filters: self.filters.clone(),
            archs: vec![self.arch.clone()],
            arch_points: Vec::new(),
            images: vec![self.image],
            reference_rays: REFERENCE_RAYS,
            budgets: self.budgets.clone(),
            cost_limits: self.cost_limits,
            hash: crate::output::provenance::hash(name.as_bytes()),
            name,
            limits: self.limits,
        }
    }
}

/// A chosen configuration and why.
#[derive(Clone, Debug, Serialize)]
pub struct Plan {
    /// The budgets it was planned for.
    pub budgets: Vec<Budget>,
    /// The configuration, at the measurement's image size.
    pub config: RenderConfig,
    /// The pick, as measured.
    pub pick: Candidate,
    /// Whether the pick meets every budget.
    pub meets: bool,
    /// The architecture the candidates were costed on.
    pub arch: String,
    /// What the pick minimises.
    pub objective: Objective,
    /// The most the pick may cost.
    pub cost_limits: CostLimits,
    /// The thinnest gap between surfaces (1st percentile), in 16-bit steps.
    pub gap_lsbs: f64,
    /// Whether the scene has open surfaces.
    pub open_surfaces: bool,
    /// How many candidates were measured.
    pub candidates: usize,
    /// How many of them meet every budget.
    pub meeting: usize,
    /// The runners-up: the cheaper candidates nearest the pick (each
    /// missing a budget), then the next dearer ones meeting every budget.
    pub runners_up: Vec<RunnerUp>,
    /// The reasons, one line each.
    pub reasons: Vec<String>,
    /// The chosen map's storage under Reeves et al.'s schemes (Table 2),
    /// tiles of `REEVES_TILE`; `None` for shadow volumes, which store no map.
    pub storage: Option<StorageBytes>,
}

/// Why planning failed.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// A render failed.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The study of the candidates failed.
    #[error(transparent)]
    Study(#[from] StudyError),
    /// The spec names no budget, no candidate, or a measure twice.
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

/// Cheaper candidates the plan lists as runners-up, nearest the pick first.
const CHEAPER: usize = 5;
/// Dearer candidates meeting every budget the plan lists.
const DEARER: usize = 3;

/// A complete row as a candidate.
fn candidate(spec: &Spec, row: &Row, scene: &Scene) -> Option<Candidate> {
    let (m, c) = (row.metrics.as_ref()?, row.cost.as_ref()?);
    let configs = spec.configs();
    let cfg = render_config(spec, configs.get(row.config_index)?);
    Some(Candidate {
        label: row.render_label(),
        algorithm: row.config.algorithm.clone(),
        format: row.config.depth_format,
        map_size: row.config.map_side_texels,
        filter: row.config.filter_name,
        cycles: c.total_cycles,
        seconds: c.frame_seconds,
        bytes: c.total_dram_bytes,
        joules: c.energy_joules,
        square_metres: c.area_square_metres,
        percent: Measure::ALL.map(|x| x.percent(m)),
        rms_error: m.rms_error,
        command: cfg.command(scene),
    })
}

/// Plan `scene` within `spec`: measure every candidate, pick the cheapest
/// meeting every budget; `progress` shows the candidates' study
/// ([`crate::experiment::study::run`]: their estimated work, and how many
/// are done).
///
/// ```
/// use umbra_core::shadow::Filter;
/// use umbra_core::DepthFormatKind;
/// use umbra_sim::experiment::study::Variant;
/// use umbra_sim::{Algorithm, Limits, PlanSpec, Scene};
/// let scene = Scene::open("weiskopf-l", &Limits::DEFAULT)?;
/// let spec = PlanSpec {
///     variants: vec![Variant::new(Algorithm::First, 0.005), Variant::new(Algorithm::Midpoint, 0.0)],
///     formats: vec![DepthFormatKind::D16],
///     map_sizes: vec![128, 256],
///     filters: vec![Filter::Point, Filter::Bilinear],
///     image: [96, 72],
///     ..PlanSpec::new(&scene, vec!["acne=1%".parse()?, "misclassified=5%".parse()?])
/// };
/// let plan = umbra_sim::plan(&scene, &spec, &indicatif::ProgressBar::hidden())?;
/// assert_eq!(plan.candidates, 8);
/// assert!(spec.map_sizes.contains(&plan.config.map_size));
/// assert!(plan.pick.command.starts_with("umbra render weiskopf-l"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// See [`PlanError`].
pub fn plan(scene: &Scene, spec: &PlanSpec, progress: &ProgressBar) -> Result<Plan, PlanError> {
    if spec.budgets.is_empty() {
        return Err(PlanError::Spec("no budget to meet".into()));
    }
    if let Some((i, b)) =
        spec.budgets.iter().enumerate().find(|(i, b)| spec.budgets[..*i].iter().any(|a| a.measure == b.measure))
    {
        return Err(PlanError::Spec(format!("budget {i} ({b}) bounds {} a second time", b.measure.name())));
    }
    crate::experiment::study::map_sides("map sides", &spec.map_sizes, &spec.limits)
        .map_err(|e| PlanError::Spec(e.to_string()))?;
    let n = spec.candidates();
    if n == 0 {
        return Err(PlanError::Spec("no algorithm, format, map side or filter to choose from".into()));
    }
    let study = spec.study(scene);
    let rows = run(&study, Shard::ALL, progress)?;
    let mut all: Vec<(Candidate, usize)> =
        rows.iter().filter_map(|r| candidate(&study, r, scene).map(|c| (c, r.config_index))).collect();
    // Least first by the objective, then DRAM bytes, then the study's order.
    let (objective, limits) = (spec.objective, &spec.cost_limits);
    let least = Objective::least(all.iter().map(|(c, _)| c.costs()).collect::<Vec<_>>().iter());
    let score = |c: &Candidate| objective.score(&c.costs(), &least);
    all.sort_by(|(a, i), (b, j)| score(a).total_cmp(&score(b)).then(a.bytes.cmp(&b.bytes)).then(i.cmp(j)));
    let budgets = &spec.budgets;
    let meets_all = |c: &Candidate| c.misses(budgets, limits).is_empty();
    let meeting = all.iter().filter(|(c, _)| meets_all(c)).count();
    let first_meeting = all.iter().position(|(c, _)| meets_all(c));
    let nearest = || {
        all.iter()
            .enumerate()
            .min_by(|(_, (a, _)), (_, (b, _))| a.worst(budgets, limits).total_cmp(&b.worst(budgets, limits)))
            .map(|x| x.0)
    };
    let Some(at) = first_meeting.or_else(nearest) else {
        return Err(PlanError::Spec(format!("none of the {n} candidates could be rendered at this image")));
    };
    let (pick, index) = all[at].clone();
    let meets = first_meeting.is_some();
    // Runners-up that render alike to one listed (a shadow volume's at
    // every map side and filter) are listed once.
    let mut seen = vec![pick.outcome()];
    let mut fresh = |c: &Candidate| {
        let new = !seen.contains(&c.outcome());
        seen.push(c.outcome());
        new
    };
    let mut runners_up: Vec<RunnerUp> = all[..at]
        .iter()
        .rev()
        .filter(|(c, _)| fresh(c))
        .take(CHEAPER)
        .map(|(c, _)| {
            let missed = c.misses(budgets, limits);
            let lost = if missed.is_empty() { "nearer every budget".to_owned() } else { missed.join(", ") };
            RunnerUp { candidate: c.clone(), cheaper: true, lost }
        })
        .collect();
    let dearer = |c: &Candidate| 100.0 * (score(c) / score(&pick) - 1.0);
    let meeting_dearer = all[at + 1..].iter().filter(|(c, _)| meets_all(c) && fresh(c));
    runners_up.extend(meeting_dearer.take(DEARER).map(|(c, _)| {
        let lost = if score(c).total_cmp(&score(&pick)).is_eq() {
            format!(
                "meets every budget at as little {}, {} more DRAM bytes",
                objective.words(),
                c.bytes.saturating_sub(pick.bytes)
            )
        } else if score(&pick) > 0.0 {
            format!("meets every budget, {:.1} % more {}", dearer(c), objective.words())
        } else {
            format!("meets every budget at {}", objective.text(&c.costs(), &least))
        };
        RunnerUp { candidate: c.clone(), cheaper: false, lost }
    }));

    let open_surfaces = scene.objects.iter().any(|o| !o.solid);
    let gap_map = spec.map_sizes.iter().copied().max().unwrap_or(512).min(1024);
    let gap_lsbs = thinnest_gap(scene, gap_map)?;
    let list = budgets.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ");
    let mut reasons = vec![format!(
        "{n} candidates ({} algorithm variants × {} depth formats × {} map sides × {} filters), each rendered at {}×{}, measured against the {REFERENCE_RAYS}×{REFERENCE_RAYS}-ray reference and costed on {}; {meeting} meet every budget ({list})",
        spec.variants.len(),
        spec.formats.len(),
        spec.map_sizes.len(),
        spec.filters.len(),
        spec.image[0],
        spec.image[1],
        spec.arch.name
    )];
    if meets {
        reasons.push(format!(
            "{}: the least {} of them on {} ({}{} cycles, {:.3} ms, {:.3} µJ, {:.4} mm² of silicon), {} candidates ranked before it missing a budget{}",
            pick.label,
            objective.words(),
            spec.arch.name,
            if objective == Objective::Cycles { String::new() } else { format!("{}; ", objective.text(&pick.costs(), &least)) },
            pick.cycles,
            pick.seconds * 1e3,
            pick.joules * 1e6,
            pick.square_metres * 1e6,
            at,
            if limits.max_square_metres.is_some() || limits.max_joules.is_some() { " or a limit" } else { "" }
        ));
        reasons.extend(why::against_fastest(&study, spec, (&all, &least), (&pick, index)));
    } else {
        reasons.push(format!(
            "no candidate meets every budget and limit: {}, the nearest (its worst measure {:.2}× its budget or limit), is taken",
            pick.label,
            pick.worst(budgets, limits)
        ));
    }
    if open_surfaces {
        let names: Vec<&str> = scene.objects.iter().filter(|o| !o.solid).map(|o| o.name.as_str()).collect();
        reasons.push(format!(
            "open surfaces ({}) have no back: tests that take the second surface from culling front faces see through them where they are single",
            names.join(", ")
        ));
    }
    reasons.push(if gap_lsbs >= GAP_LSBS {
        format!(
            "thinnest gaps between surfaces span {gap_lsbs:.0} 16-bit steps (1st percentile, {gap_map}² f32 map) ≥ {GAP_LSBS}: 16-bit depth can hold the midpoint tests' reference"
        )
    } else {
        format!(
            "thinnest gaps between surfaces span only {gap_lsbs:.1} 16-bit steps (1st percentile, {gap_map}² f32 map) < {GAP_LSBS}: 16-bit depth cannot hold the midpoint tests' reference everywhere"
        )
    });
    let configs = study.configs();
    let config = render_config(&study, &configs[index]);
    let r = render(&config.check(scene, &spec.limits)?, TruthSource::Quiet)?;
    // Every map the pick draws: each cascade's beside the first.
    let stored = |maps: &light::RawMaps| {
        let raster = maps.maps.config.raster;
        let shape = MapShape::of_format(raster.width(), raster.height(), maps.format);
        storage_bytes(&shape, &maps.buffers(), REEVES_TILE).map_err(|e| PlanError::Spec(format!("map storage: {e}")))
    };
    let storage = if config.algorithm == crate::pass::algorithm::Algorithm::Volumes {
        None
    } else {
        let mut all = stored(&r.maps)?;
        for maps in &r.cascade_maps {
            all = all.plus(&stored(maps)?);
        }
        Some(all)
    };
    Ok(Plan {
        budgets: budgets.clone(),
        config,
        pick,
        meets,
        arch: spec.arch.name.clone(),
        objective,
        cost_limits: *limits,
        gap_lsbs,
        open_surfaces,
        candidates: all.len(),
        meeting,
        runners_up,
        reasons,
        storage,
    })
}
