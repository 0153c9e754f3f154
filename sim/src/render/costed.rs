//! A render's cost on architectures ([`crate::cost::arch`], timed by
//! [`crate::cost::timing`]), in as few passes as their tilings allow.
//!
//! An architecture's timing model needs the passes' events in its own tiles
//! (and, for a depth cache, each fragment's address), so architectures
//! that share a tiling and that detail are costed from one pass's events,
//! each through its own probe ([`Fan`]); the functional render's passes
//! cost those whose tiling is its own.

use umbra_core::shadow::Filter;
use umbra_core::silhouette::{Packed, SilPoint, SilStore};
use umbra_core::{DepthFormat, DepthFormatKind, RasterConfig};

use super::{
    Algorithm, Checked, MapSlot, Render, RenderConfig, RenderError, Targets, TruthSource, map_slots, passes, render_in,
};
use crate::base::maps::{Tiling, with_format};
use crate::base::probes::Fan;
use crate::cost::arch::Arch;
use crate::cost::report::CostReport;
use crate::cost::silicon::{Demand, Silicon};
use crate::cost::timing::{ArchProbe, PassKind};
use crate::input::limits::Limits;
use crate::pass::algorithm::{MapKind, Units};
use crate::pass::camera::{CameraFrame, lit_pass, visibility};
use crate::world::occluders::Lit;
use crate::world::scene::Scene;

/// How an architecture needs the passes drawn: its [`Tiling`], and
/// whether its light and camera passes need each fragment's address (a
/// depth cache in front of off-chip depth). Architectures with the same
/// shape are costed from one run of the passes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Shape {
    pub(super) tiling: Tiling,
    pub(super) light_addresses: bool,
    pub(super) camera_addresses: bool,
}

pub(super) fn shape(arch: &Arch) -> Shape {
    let cached = arch.depth_cache.size > 0;
    Shape {
        tiling: arch.tiling(),
        light_addresses: cached && !arch.on_chip.light_depth,
        camera_addresses: cached && !arch.on_chip.camera_depth,
    }
}

/// The depth samples a lookup of `cfg` takes, and whether it weighs them
/// bilinearly: its filter's (Sen et al.'s figure), or for a silhouette
/// map the four at its texel's corners whatever the filter
/// ([`umbra_core::silhouette::DEPTH_SAMPLES`]).
const fn lookup_samples(cfg: &RenderConfig) -> (u64, bool) {
    match (cfg.algorithm, cfg.filter) {
        (Algorithm::Silhouette { .. }, _) => (umbra_core::silhouette::DEPTH_SAMPLES as u64, false),
        (_, Filter::Point) => (1, false),
        (_, Filter::Bilinear) => (4, true),
        (_, Filter::Box { size }) => (size as u64 * size as u64, false),
        (_, Filter::Jittered(j)) => (j.num_samples as u64, false),
    }
}

impl RenderConfig {
    /// What this configuration asks of the hardware, as silicon is
    /// counted ([`crate::cost::silicon`]).
    ///
    /// ```
    /// use umbra_sim::RenderConfig;
    /// let d = RenderConfig::DEFAULT.demand();
    /// assert_eq!((d.depth_buffers, d.depth_bits), (2, 24));
    /// ```
    #[must_use]
    pub fn demand(&self) -> Demand {
        demand(self)
    }
}

/// What `cfg` asks of the hardware, as silicon is counted.
fn demand(cfg: &RenderConfig) -> Demand {
    let units = cfg.algorithm.units::<umbra_core::D24>(cfg.bias);
    let (samples, bilinear) = lookup_samples(cfg);
    let two = matches!(cfg.algorithm, Algorithm::Midpoint | Algorithm::Dual { .. });
    let silhouette_bits = match units.map {
        MapKind::Silhouette { packed: true } => 8 * Packed::BYTES,
        MapKind::Silhouette { packed: false } => 8 * SilPoint::BYTES,
        MapKind::Depth | MapKind::Volumes => 0,
    };
    Demand {
        depth_buffers: units.unit.buffers(),
        depth_bits: cfg.format.bits(),
        map: [largest_map(cfg); 2],
        image: [cfg.width, cfg.height],
        buffers_read: if two { 2 } else { 1 },
        samples_per_lookup: u32::try_from(samples).unwrap_or(u32::MAX),
        bilinear,
        offset: two,
        bias_range: matches!(cfg.algorithm, Algorithm::BiasRange { .. }),
        virtual_samples: units.virtual_samples(cfg.virtual_samples),
        silhouette_bits,
        volumes: units.map == MapKind::Volumes,
    }
}

/// The largest map side `cfg` draws: its map's, or the largest cascade's
/// it asks for (the bin heads' count follows it).
fn largest_map(cfg: &RenderConfig) -> u32 {
    cfg.cascades.map_or(cfg.map_size, |c| (0..c.count()).map(|k| c.side(k, cfg.map_size)).max().unwrap_or(cfg.map_size))
}

/// The camera pass's probe of `arch` for `cfg` on `image`: one that reads
/// the map through the map cache when the pass is `shadowed` by one.
fn camera_probe<const C: bool>(
    arch: &Arch,
    cfg: &RenderConfig,
    image: RasterConfig,
    units: &Units,
    shadowed: bool,
) -> ArchProbe<C> {
    reading(ArchProbe::<C>::new(arch, PassKind::Camera, image, DepthFormatKind::D24, 1), cfg, units, shadowed)
}

/// `probe` reading the map `cfg` and `units` draw, when the pass is `shadowed` by one.
pub(super) fn reading<const C: bool>(
    probe: ArchProbe<C>,
    cfg: &RenderConfig,
    units: &Units,
    shadowed: bool,
) -> ArchProbe<C> {
    if !shadowed || units.map == MapKind::Volumes {
        return probe;
    }
    let sil = if units.map == (MapKind::Silhouette { packed: true }) { Packed::BYTES } else { SilPoint::BYTES };
    probe.reading(units.unit.buffers(), cfg.format.bytes(), sil, lookup_samples(cfg))
}

/// The passes' probes of `archs` for `cfg` on `checked`: each light
/// pass's (one per map of `slots`, or one on the map target when the
/// pass is not `shadowed`), the camera pass's.
fn probes<F: DepthFormat, const L: bool, const C: bool>(
    cfg: &RenderConfig,
    (checked, slots): (Targets, &[MapSlot]),
    archs: &[&Arch],
    shadowed: bool,
) -> (Vec<Fan<ArchProbe<L>>>, Fan<ArchProbe<C>>) {
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let light = |raster| {
        Fan(archs
            .iter()
            .map(|a| ArchProbe::<L>::new(a, PassKind::Light, raster, cfg.format, units.unit.buffers()))
            .collect())
    };
    let camera = archs.iter().map(|a| camera_probe::<C>(a, cfg, checked.image, &units, shadowed)).collect();
    let rasters: Vec<RasterConfig> =
        if shadowed && !slots.is_empty() { slots.iter().map(|s| s.raster).collect() } else { vec![checked.map] };
    (rasters.into_iter().map(light).collect(), Fan(camera))
}

/// Each map's name in a cost report's timeline ([`MapSlot::key`]), and
/// the shadings a pixel gets (one a light).
pub(super) fn map_names(slots: &[MapSlot]) -> (Vec<String>, usize) {
    let lights = slots.iter().map(|s| s.light + 1).max().unwrap_or(1);
    let cascaded = |k: usize| slots.iter().filter(|s| s.light == k).count() > 1;
    (slots.iter().map(|s| s.key(cascaded(s.light))).collect(), lights)
}

/// What a cost report says of the scene beside its passes: its triangles
/// and its occluders' silhouette edges (Sen et al.'s bandwidth model),
/// and its maps' names and the shadings a pixel gets ([`map_names`]).
#[derive(Clone, Debug)]
pub(super) struct SceneCounts {
    triangles: u64,
    silhouette_edges: u64,
    maps: (Vec<String>, usize),
}

impl SceneCounts {
    /// The counts of `scene`, lit by each of its lights as `lit` holds it:
    /// the silhouette edges are its first light's.
    /// (`slots` empty: one map a light, as a shared study draws them.)
    pub(super) fn of(scene: &Scene, lit: &[Lit<'_>], slots: &[MapSlot]) -> Self {
        let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
        let edges = lit.first().map_or(0, |l| l.occluders().silhouette_edges().len());
        let maps = if slots.is_empty() {
            ((0..lit.len()).map(Scene::light_key).collect(), lit.len())
        } else {
            map_names(slots)
        };
        Self { triangles: triangles as u64, silhouette_edges: edges as u64, maps }
    }
}

/// The report of one architecture's probes (each light pass's, the
/// camera pass's), once the passes have run.
pub(super) fn report<const L: bool, const C: bool>(
    (scene, counts): (&str, &SceneCounts),
    cfg: &RenderConfig,
    config: &str,
    mut lights: Vec<ArchProbe<L>>,
    mut camera: ArchProbe<C>,
) -> CostReport {
    lights.iter_mut().for_each(ArchProbe::finish);
    camera.finish();
    let silicon = Silicon::of(&camera.arch, &demand(cfg));
    let (names, shadings) = &counts.maps;
    let samples = (lookup_samples(cfg).0, *shadings);
    let mut r = CostReport::new((scene, config.to_owned()), (&lights, names), &camera, samples).with_silicon(silicon);
    r.sen.triangles = counts.triangles;
    r.sen.silhouette_edges = counts.silhouette_edges;
    r
}

/// The reports of the probes, once the passes have run.
fn reports<const L: bool, const C: bool>(
    (scene, counts): (&Scene, SceneCounts),
    cfg: &RenderConfig,
    config: &str,
    lights: Vec<Fan<ArchProbe<L>>>,
    Fan(camera): Fan<ArchProbe<C>>,
) -> Vec<CostReport> {
    if camera.is_empty() {
        return Vec::new();
    }
    // Per light, per architecture: per architecture, per light.
    let mut per_arch: Vec<Vec<ArchProbe<L>>> = camera.iter().map(|_| Vec::with_capacity(lights.len())).collect();
    for Fan(probes) in lights {
        per_arch.iter_mut().zip(probes).for_each(|(mine, p)| mine.push(p));
    }
    per_arch.into_iter().zip(camera).map(|(l, c)| report((&scene.name, &counts), cfg, config, l, c)).collect()
}

/// The cost of a render, checked for its scene ([`RenderConfig::check`]),
/// on an architecture: both passes through
/// its timing model, the light pass and the camera's visibility in the
/// architecture's tiles.
///
/// ```
/// use umbra_sim::{Arch, Limits, RenderConfig, Scene};
/// let scene = Scene::open("weiskopf-l", &Limits::DEFAULT)?;
/// let cfg = RenderConfig { width: 96, height: 72, map_size: 128, ..RenderConfig::DEFAULT };
/// let (slow, fast) = (Arch::open("pixelflow", &Limits::DEFAULT)?, Arch::open("desktop-imr", &Limits::DEFAULT)?);
/// let job = cfg.check(&scene, &Limits::DEFAULT)?;
/// let cost = |a: &Arch| umbra_sim::cost(&job, a);
/// // The same frame, the same events: the machines differ in time only.
/// assert_eq!(cost(&slow)?.pixels, cost(&fast)?.pixels);
/// assert!(cost(&slow)?.seconds() > cost(&fast)?.seconds());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// See [`RenderError`].
pub fn cost(job: &Checked<'_>, arch: &Arch) -> Result<CostReport, RenderError> {
    cost_group(job, &Lit::each(job.scene()), &[arch], true).map(|mut r| r.remove(0))
}

/// The cost of drawing `scene` from its camera at `width × height` without
/// shadows: the visibility pass and every covered pixel shaded, no light
/// pass and no shadow unit (the baseline frame rates are measured against).
///
/// # Errors
/// See [`RenderError`].
pub(crate) fn cost_unshadowed(
    scene: &Scene,
    (width, height): (u32, u32),
    arch: &Arch,
    limits: &Limits,
) -> Result<CostReport, RenderError> {
    let cfg = RenderConfig {
        algorithm: Algorithm::First,
        format: DepthFormatKind::D24,
        map_size: 8,
        filter: Filter::Point,
        virtual_samples: false,
        width,
        height,
        reference_rays: 1,
        ..RenderConfig::DEFAULT
    };
    cost_group(&cfg.check(scene, limits)?, &Lit::each(scene), &[arch], false).map(|mut r| r.remove(0))
}

/// The cost on `archs`, which share a [`Shape`] (the first's), from one
/// run of the passes of `job`'s scene lit as `lit` holds it.
fn cost_group(
    job: &Checked<'_>,
    lit: &[Lit<'_>],
    archs: &[&Arch],
    shadowed: bool,
) -> Result<Vec<CostReport>, RenderError> {
    let Some(first) = archs.first() else { return Ok(Vec::new()) };
    let (scene, cfg) = (job.scene(), job.config());
    let Shape { tiling, light_addresses: light_detail, camera_addresses: camera_detail } = shape(first);
    let checked = job.targets(tiling.tile)?;
    let scene = (scene, lit);
    with_format!(cfg.format, F => match (light_detail, camera_detail) {
        (false, false) => cost_in::<F, false, false>(scene, cfg, checked, archs, shadowed),
        (true, false) => cost_in::<F, true, false>(scene, cfg, checked, archs, shadowed),
        (false, true) => cost_in::<F, false, true>(scene, cfg, checked, archs, shadowed),
        (true, true) => cost_in::<F, true, true>(scene, cfg, checked, archs, shadowed),
    })
}

fn cost_in<F: DepthFormat, const L: bool, const C: bool>(
    (scene, lit): (&Scene, &[Lit<'_>]),
    cfg: &RenderConfig,
    checked: Targets,
    archs: &[&Arch],
    shadowed: bool,
) -> Result<Vec<CostReport>, RenderError> {
    let slots = if shadowed { map_slots(scene, cfg, checked.map)? } else { Vec::new() };
    let (mut light, mut camera) = probes::<F, L, C>(cfg, (checked, &slots), archs, shadowed);
    let drawing = archs.first().map_or(Tiling::DEFAULT, |a| a.tiling());
    let config = if shadowed {
        let frames = &mut Vec::new();
        let targets = (checked, slots.as_slice());
        light = passes::<F, _, _>((scene, lit), cfg, targets, frames, light, &mut camera, drawing)?.light_probes;
        cfg.describe()
    } else {
        let mut frame = CameraFrame::default();
        let size = (checked.image.width(), checked.image.height());
        visibility(&mut frame, scene, size, drawing, &mut camera)?;
        lit_pass(frame.ids(), size.0, &mut camera);
        format!("no shadow, image {}x{}", cfg.width, cfg.height)
    };
    Ok(reports((scene, SceneCounts::of(scene, lit, &slots)), cfg, &config, light, camera))
}

/// The render of `cfg` (as [`super::render`]) and its cost on each
/// of `archs` (as [`cost`], in their order), in as few passes as their
/// tilings allow: the render's own passes cost the architectures that draw
/// as it does (32-pixel tiles, no per-draw finish, no fragment detail), and
/// each other tiling's architectures share one run of the passes. A
/// costing that fails is that architecture's error.
///
/// # Errors
/// The render's [`RenderError`].
pub fn render_costed(
    job: &Checked<'_>,
    truth_from: TruthSource<'_>,
    archs: &[Arch],
) -> Result<(Render, Vec<Result<CostReport, RenderError>>), RenderError> {
    let own = Shape { tiling: Tiling::DEFAULT, light_addresses: false, camera_addresses: false };
    let (scene, cfg) = (job.scene(), job.config());
    let checked = job.targets(RasterConfig::DEFAULT_TILE_SIZE)?;
    let shared: Vec<&Arch> = archs.iter().filter(|a| shape(a) == own).collect();
    let lit = Lit::each(scene);
    let slots = map_slots(scene, cfg, checked.map)?;
    let counts = SceneCounts::of(scene, &lit, &slots);
    let (render, costed) = with_format!(cfg.format, F => {
        let (light, mut camera) = probes::<F, false, false>(cfg, (checked, &slots), &shared, true);
        let (render, light) = render_in::<F, _, _>((scene, &lit), cfg, checked, truth_from, (light, &mut camera))?;
        (render, reports((scene, counts), cfg, &cfg.describe(), light, camera))
    });
    // The shared reports, in the architectures' order.
    let mut costed = costed.into_iter();
    let mut out: Vec<Option<Result<CostReport, RenderError>>> =
        archs.iter().map(|a| if shape(a) == own { costed.next().map(Ok) } else { None }).collect();
    // The other tilings, each group in one run.
    cost_others((job, &lit), archs, &mut out);
    Ok((render, out.into_iter().map(|r| r.unwrap_or_else(|| Err(RenderError::Cost("not costed".into())))).collect()))
}

/// The cost on each of `archs` that `out` does not hold yet, each shape's
/// architectures from one run of the passes (as [`render_costed`] costs
/// those that do not draw as the render does). A costing that fails is
/// that architecture's error.
pub(crate) fn cost_others(
    (job, lit): (&Checked<'_>, &[Lit<'_>]),
    archs: &[Arch],
    out: &mut [Option<Result<CostReport, RenderError>>],
) {
    let mut groups: Vec<(Shape, Vec<usize>)> = Vec::new();
    for (k, a) in archs.iter().enumerate().filter(|&(k, _)| out[k].is_none()) {
        match groups.iter_mut().find(|g| g.0 == shape(a)) {
            Some(g) => g.1.push(k),
            None => groups.push((shape(a), vec![k])),
        }
    }
    for (_, members) in groups {
        let group: Vec<&Arch> = members.iter().map(|&k| &archs[k]).collect();
        match cost_group(job, lit, &group, true) {
            Ok(reports) => members.iter().zip(reports).for_each(|(&k, r)| out[k] = Some(Ok(r))),
            Err(e) => {
                let text = e.to_string();
                members.iter().for_each(|&k| out[k] = Some(Err(RenderError::Cost(text.clone()))));
            }
        }
    }
}
