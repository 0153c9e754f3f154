//! One render of a [`RenderConfig`]: the light pass for a shadow
//! algorithm, the camera pass, the exact reference and the metrics between
//! them ([`render`]); its cost on
//! architectures (`costed`); its pictures ([`pictures`]). This layer sits
//! above the passes, the cost model and the truth, and joins them.

pub mod arrays;
#[cfg(test)]
mod cache_trace;
mod config;
mod costed;
pub mod files;
#[cfg(test)]
mod ledger_property;
pub mod params;
pub mod pictures;
mod produced;
pub mod replay;
mod request;
pub(crate) mod shared;

use indicatif::ProgressBar;
use umbra_core::depth::Texel;
use umbra_core::shade::{MapUnit, ShadowUnit, SilhouetteUnit};
use umbra_core::shadow::{MapView, ShadowConfig, ShadowConfigError};
use umbra_core::silhouette::SilStore;
use umbra_core::{DepthFormat, DepthUnit, LightPassConfig, Probe, RasterConfig, TileState};

pub(crate) use self::config::Targets;
pub use self::config::{Checked, RenderConfig, RenderConfigError};
pub use self::costed::{cost, render_costed};
pub(crate) use self::costed::{cost_others, cost_unshadowed};
pub use self::produced::{LightPart, PartRef, Render};
use self::replay::{PassInputs, ShadowSource, judged};
pub use self::request::RenderRequest;
use crate::base::counters::Counters;
use crate::base::maps::{Tiling, with_format};
use crate::base::probes::Tee;
use crate::input::limits::LimitError;
use crate::pass::PassError;
use crate::pass::algorithm::MapKind;
pub(crate) use crate::pass::algorithm::{Algorithm, Culling};
use crate::pass::camera::{CameraFrame, CameraImage, CameraOptions, map_view, shade_visible, visibility, volumes};
use crate::pass::light::{self, DEFAULT_BIN_CAPACITY, LightFrame, LightMaps, LightOptions, RawMaps};
use crate::pass::occluders::{SilReader, SilTexels};
use crate::truth::metrics::Fields;
use crate::truth::reference::{PixelTruth, Reference, ReferenceError};
use crate::world::occluders::Lit;
use crate::world::scene::{LightSource, Scene};

/// Why a render failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The configuration asks for what no render takes.
    #[error(transparent)]
    Config(#[from] RenderConfigError),
    /// Costing on an architecture failed (in a pass shared with others).
    #[error("cost: {0}")]
    Cost(String),
    /// The light or camera pass could not run.
    #[error(transparent)]
    Pass(#[from] PassError),
    /// The shadow configuration is unusable.
    #[error("shadow configuration: {0}")]
    Shadow(#[from] ShadowConfigError),
    /// The reference could not be built.
    #[error(transparent)]
    Reference(#[from] ReferenceError),
    /// The architecture's cache geometry is unusable.
    #[error("map cache: {0}")]
    Cache(String),
    /// The map size is unusable.
    #[error("map: {0}")]
    MapSize(umbra_core::ConfigError),
    /// The camera image size is unusable.
    #[error("camera image: {0}")]
    ImageSize(umbra_core::ConfigError),
    /// A reference built for another image size.
    #[error("the reference has {found} pixels, the {width}x{height} image needs {}", *width as u64 * *height as u64)]
    Truth {
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
        /// Pixels the reference has.
        found: usize,
    },
    /// The map, the image or the scene is beyond the `Limits`.
    #[error(transparent)]
    Limit(#[from] LimitError),
    /// The camera sees no surface facing the light: there is no pixel to
    /// measure (never a result of 0 % error). Its near and far planes are
    /// named: a near plane far below the far one leaves the f32 depth no
    /// room to tell a surface from the far plane.
    #[error(
        "camera: the view shows no surface facing the light (its near plane {near:e}, far {far}: check them, its direction, and the light), so no pixel can be evaluated"
    )]
    NothingEvaluated {
        /// The camera's near plane.
        near: f32,
        /// Its far plane.
        far: f32,
    },
    /// The light's map receives no fragment: the light sees no object.
    #[error(transparent)]
    EmptyMap(#[from] crate::pass::light::EmptyMap),
    /// One of several lights faces no surface the camera sees.
    #[error("{0}: the view shows no surface facing this light, so none of its pixels can be evaluated")]
    NothingEvaluatedFor(String),
    /// References given for another number of lights.
    #[error("{found} references were given for the scene's {lights} shadow-casting lights")]
    Truths {
        /// The scene's shadow-casting lights.
        lights: usize,
        /// The references given.
        found: usize,
    },
    /// A problem of one of several lights' parts.
    #[error("{light}: {source}")]
    OfLight {
        /// The light, `lights[k]`.
        light: String,
        /// What went wrong.
        source: Box<RenderError>,
    },
    /// A stop was requested while the reference was built.
    #[error(transparent)]
    Stopped(#[from] crate::base::stop::Stopped),
}

impl RenderError {
    /// [`RenderError::NothingEvaluated`] of `scene`'s camera.
    fn nothing_evaluated(scene: &Scene) -> Self {
        let (near, far) = scene.camera.planes();
        Self::NothingEvaluated { near, far }
    }

    /// This error as light `k`'s.
    #[must_use]
    pub fn of_light(self, k: usize) -> Self {
        Self::OfLight { light: Scene::light_key(k), source: Box::new(self) }
    }
}

/// Where a render's exact reference comes from.
pub enum TruthSource<'p> {
    /// Built for this render, showing no progress.
    Quiet,
    /// Built for this render; the bar ticks once per reference row and
    /// light.
    Build(&'p ProgressBar),
    /// Built before ([`truth`]) for the same scene, image size and rays:
    /// one per shadow-casting light.
    Given(Vec<Vec<Option<PixelTruth>>>),
}

/// Render the configuration `job` checked for its scene
/// ([`RenderConfig::check`]), against the exact reference `truth_from`
/// names.
///
/// ```
/// use umbra_sim::{Limits, RenderConfig, Scene, TruthSource};
/// let scene = Scene::open("weiskopf-l", &Limits::DEFAULT)?;
/// let cfg = RenderConfig { width: 96, height: 72, map_size: 128, ..RenderConfig::DEFAULT };
/// let r = umbra_sim::render(&cfg.check(&scene, &Limits::DEFAULT)?, TruthSource::Quiet)?;
/// let m = &r.metrics;
/// assert_eq!(m.evaluated as usize, r.truth.iter().flatten().filter(|t| t.faces_light).count());
/// assert!(m.aliasing + m.penumbra + m.acne + m.detachment + m.leaks <= m.evaluated);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// See [`RenderError`].
pub fn render(job: &Checked<'_>, truth_from: TruthSource<'_>) -> Result<Render, RenderError> {
    let (scene, cfg) = (job.scene(), job.config());
    let checked = job.targets(RasterConfig::DEFAULT_TILE_SIZE)?;
    let none = (vec![umbra_core::NoProbe; scene.lights.len().max(1)], &mut umbra_core::NoProbe);
    let lit = Lit::each(scene);
    Ok(with_format!(cfg.format, F => render_in::<F, _, _>((scene, &lit), cfg, checked, truth_from, none)?.0))
}

/// The references `truth_from` names for the render's image, one per
/// light, of the configuration's image size: one built is cast through the
/// triangles the render's own camera pass saw (the visibility of
/// [`truth`], bit for bit).
fn truths_of(
    cfg: &RenderConfig,
    truth_from: TruthSource<'_>,
    (ids, camera): (&[u32], umbra_core::glam::Mat4),
    (reference, lights): (&Reference, &[LightSource]),
    scene: &Scene,
) -> Result<Vec<Vec<Option<PixelTruth>>>, RenderError> {
    let build = |progress: &ProgressBar| {
        lights
            .iter()
            .map(|light| reference.image(ids, &camera, cfg.width, cfg.height, light, cfg.reference_rays, progress))
            .collect::<Vec<_>>()
    };
    let truths = match truth_from {
        TruthSource::Quiet => build(&ProgressBar::hidden()),
        TruthSource::Build(progress) => build(progress),
        TruthSource::Given(t) => t,
    };
    // A reference cut short by a stop is not one.
    crate::base::stop::check()?;
    let pixels = u64::from(cfg.width) * u64::from(cfg.height);
    if truths.len() != lights.len() {
        return Err(RenderError::Truths { lights: lights.len(), found: truths.len() });
    }
    for (k, truth) in truths.iter().enumerate() {
        if truth.len() as u64 != pixels {
            return Err(RenderError::Truth { width: cfg.width, height: cfg.height, found: truth.len() });
        }
        if !truth.iter().flatten().any(|t| t.faces_light) {
            return Err(if lights.len() == 1 {
                RenderError::nothing_evaluated(scene)
            } else {
                RenderError::NothingEvaluatedFor(Scene::light_key(k))
            });
        }
    }
    Ok(truths)
}

/// The exact reference of `scene` seen from its camera at `width × height`
/// with `samples²` rays per pixel (see [`Reference::image`]), one per
/// shadow-casting light. It depends on nothing else, so a sweep builds it
/// once per scene and image.
///
/// # Errors
/// See [`RenderError`]; [`RenderError::Stopped`] when a stop was
/// requested before it was whole.
pub fn truth(
    scene: &Scene,
    width: u32,
    height: u32,
    samples: u32,
    progress: &ProgressBar,
) -> Result<Vec<Vec<Option<PixelTruth>>>, RenderError> {
    let mut frame = CameraFrame::default();
    let vis = visibility(&mut frame, scene, (width, height), Tiling::DEFAULT, &mut umbra_core::NoProbe)?;
    let reference = Reference::of(scene)?;
    let lights = light_sources(scene);
    let truths =
        lights.iter().map(|l| reference.image(frame.ids(), &vis.camera, width, height, l, samples, progress)).collect();
    crate::base::stop::check()?;
    Ok(truths)
}

/// Each shadow-casting light as the exact reference sees it.
fn light_sources(scene: &Scene) -> Vec<LightSource> {
    match scene.lights.as_slice() {
        [] => vec![scene.light().source()],
        lights => lights.iter().map(crate::world::scene::Light::source).collect(),
    }
}

/// Tell `probe` that the shadow unit reads light `k`'s map, when the pass
/// tests more than one of `lights`.
fn bind<P: Probe>(probe: &mut P, k: usize, lights: usize) {
    if lights > 1 {
        probe.map_bound(u16::try_from(k).unwrap_or(u16::MAX));
    }
}

/// The camera pass's options for `cfg`, whose algorithm uses `units`, at
/// `size` in `tiling`.
///
/// # Errors
/// [`RenderError::Shadow`] for a shadow configuration the unit refuses.
pub(crate) fn camera_options(
    cfg: &RenderConfig,
    units: &crate::pass::algorithm::Units,
    (width, height): (u32, u32),
    tiling: Tiling,
) -> Result<CameraOptions, RenderError> {
    Ok(CameraOptions {
        width,
        height,
        shadow: ShadowConfig::new(units.test, units.bias, cfg.filter, true)?,
        virtual_samples: units.virtual_samples(cfg.virtual_samples),
        tiling,
    })
}

/// The passes of a render of `scene`, lit by each of its lights as `lit`
/// holds it ([`Lit::each`]): a light pass per shadow-casting light, each
/// reporting to its own of `light_probes` (one per light) and drawing into
/// its own of `frames` (with its silhouette pass, for a silhouette map),
/// then the camera pass: the visibility unit once and the shading unit
/// once per light against that light's map (the probe told which map it
/// reads), or the stencil unit once per light for shadow volumes. The
/// light probes, one camera image per light, and each light's silhouette
/// map (none for other algorithms), for the judge to read.
pub(super) fn passes<F: DepthFormat, L: Probe, C: Probe>(
    (scene, lit): (&Scene, &[Lit<'_>]),
    cfg: &RenderConfig,
    checked: Targets,
    frames: &mut Vec<LightFrame<F::Texel>>,
    light_probes: Vec<L>,
    camera_probe: &mut C,
    tiling: Tiling,
) -> Result<Passes<L>, RenderError> {
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let light_config = LightPassConfig { raster: checked.map, unit: units.unit, max_z_cull: true };
    let mut camera = CameraFrame::default();
    let size = (checked.image.width(), checked.image.height());
    debug_assert_eq!(light_probes.len(), lit.len(), "one light probe per light");
    let triangles = scene.triangles();
    if units.map == MapKind::Volumes {
        let images = volumes(&mut camera, (scene, &triangles, lit), size, tiling, camera_probe)?;
        return Ok(Passes { light_probes, images, silhouettes: Vec::new(), triangles });
    }
    frames.resize_with(lit.len(), LightFrame::new);
    let drawing = LightOptions { per_draw: tiling.per_draw, ..LightOptions::default() };
    let mut views = Vec::with_capacity(lit.len());
    let mut probes = Vec::with_capacity(lit.len());
    for ((one, frame), probe) in lit.iter().map(|l| &*l.scene).zip(frames.iter_mut()).zip(light_probes) {
        let draws = one.draws_culled(one.light().view_projection(), |solid| units.cull(solid, cfg.culling));
        let (maps, probe) = light::render::<F, _, DEFAULT_BIN_CAPACITY>(frame, light_config, &draws, drawing, probe)?;
        views.push(map_view::<F>(maps, units.front_culled)?);
        probes.push(probe);
    }
    let options = camera_options(cfg, &units, size, tiling)?;
    let mut silhouettes = Vec::new();
    if let MapKind::Silhouette { packed } = units.map {
        // Each light's silhouette pass over its map, its events to its
        // light probe (part of the light side).
        for ((one, view), probe) in lit.iter().zip(&views).zip(probes.iter_mut()) {
            let light = one.scene.light().view_projection();
            let texels = SilTexels::draw(packed, one.occluders(), &light, view, options.shadow, probe)
                .map_err(PassError::from)?;
            silhouettes.push(texels);
        }
    }
    visibility(&mut camera, scene, size, tiling, camera_probe)?;
    let mut images = Vec::with_capacity(lit.len());
    for (k, (one, view)) in lit.iter().map(|l| &*l.scene).zip(&views).enumerate() {
        bind(camera_probe, k, lit.len());
        let scene = (one, triangles.as_slice());
        let shade = Shade { camera: &mut camera, scene, view, options: &options, probe: &mut *camera_probe };
        images.push(match silhouettes.get(k) {
            Some(texels) => texels.read(view.raster(), shade).map_err(PassError::from)??,
            None => shade.read(&MapUnit)?,
        });
    }
    Ok(Passes { light_probes: probes, images, silhouettes, triangles })
}

/// What a render's passes leave ([`passes`]).
pub(super) struct Passes<L> {
    /// The light probes, one a light.
    pub(super) light_probes: Vec<L>,
    /// One camera image a light.
    pub(super) images: Vec<CameraImage>,
    /// Each light's silhouette map, for an algorithm that draws one.
    pub(super) silhouettes: Vec<SilTexels>,
    /// The scene's triangles ([`Scene::triangles`]), as the shading read them.
    pub(super) triangles: Vec<umbra_core::shade::SceneTriangle>,
}

/// The shading of the visible pixels against one light's map, through the
/// shadow unit it is given.
struct Shade<'a, 'v, F: DepthFormat, C> {
    camera: &'a mut CameraFrame,
    scene: (&'a Scene, &'a [umbra_core::shade::SceneTriangle]),
    view: &'a MapView<'v, F>,
    options: &'a CameraOptions,
    probe: &'a mut C,
}

impl<F: DepthFormat, C: Probe> Shade<'_, '_, F, C> {
    fn read<U: ShadowUnit<F>>(self, unit: &U) -> Result<CameraImage, RenderError> {
        Ok(shade_visible(self.camera, self.scene, self.view, unit, self.options, self.probe)?)
    }
}

impl<F: DepthFormat, C: Probe> SilReader for Shade<'_, '_, F, C> {
    type Out = Result<CameraImage, RenderError>;

    fn read<S: SilStore>(self, unit: &SilhouetteUnit<'_, '_, S>) -> Self::Out {
        Shade::read(self, unit)
    }
}

/// The render of `cfg`, its events counted, and reporting to more probes
/// besides (the architectures costed from the same passes): one per light
/// for the light passes, one for the camera pass.
pub(super) fn render_in<F: DepthFormat, L: Probe, C: Probe>(
    (scene, lit): (&Scene, &[Lit<'_>]),
    cfg: &RenderConfig,
    checked: Targets,
    truth_from: TruthSource<'_>,
    (light_also, camera_also): (Vec<L>, &mut C),
) -> Result<(Render, Vec<L>), RenderError> {
    let command = cfg.command(scene);
    let mut camera_events = Counters::new(&checked.image);
    let mut frames = Vec::new();
    let light_probes = light_also.into_iter().map(|also| Tee(Counters::new(&checked.map), also)).collect();
    let Passes { light_probes: probes, images, silhouettes, triangles } = passes::<F, _, _>(
        (scene, lit),
        cfg,
        checked,
        &mut frames,
        light_probes,
        &mut Tee(&mut camera_events, camera_also),
        Tiling::DEFAULT,
    )?;
    let (light_events, light_also): (Vec<Counters>, Vec<L>) = probes.into_iter().map(|Tee(a, b)| (a, b)).unzip();
    let several = light_events.len() > 1;
    for (k, (frame, events)) in frames.iter().zip(&light_events).enumerate() {
        if frame.maps().is_some() {
            crate::pass::light::EmptyMap::check(&events.totals, &Scene::light_key(k), Some(scene.lights[k].planes()))?;
        }
    }
    let reference = Reference::of(scene)?;
    let Some(seen) = images.first() else { return Err(RenderError::nothing_evaluated(scene)) };
    let ids: Vec<u32> = seen.pixels.iter().map(|p| p.triangle).collect();
    let truths = truths_of(cfg, truth_from, (&ids, seen.camera), (&reference, &light_sources(scene)), scene)?;
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let options = camera_options(cfg, &units, (seen.width, seen.height), Tiling::DEFAULT)?;
    let mut parts = Vec::with_capacity(images.len());
    for (k, ((image, truth), events)) in images.into_iter().zip(truths).zip(light_events).enumerate() {
        let fields = Fields::new(&truth, image.width);
        let maps = frames.get(k).and_then(LightFrame::maps);
        let view = maps.map(|m| map_view::<F>(m, units.front_culled)).transpose()?;
        let one = lit.get(k).map_or(scene, |l| &*l.scene);
        let inputs = PassInputs {
            scene: one,
            triangles: &triangles,
            seen: (&ids, image.camera),
            view: view.as_ref(),
            options: &options,
            source: ShadowSource::of(units.map, silhouettes.get(k)),
            memo: None,
        };
        let (metrics, verdicts) = judged(&inputs, &image.pixels, (&truth, &fields, &reference), None)
            .map_err(|e| if several { RenderError::Pass(e).of_light(k) } else { RenderError::Pass(e) })?;
        let maps = maps.map_or_else(
            // Shadow volumes draw no map: one far texel stands for it.
            || LightMaps {
                config: LightPassConfig { raster: checked.map, unit: DepthUnit::Single, max_z_cull: true },
                z1: vec![F::Texel::to_raw(F::FAR)],
                z2: Vec::new(),
                tiles: vec![TileState::cleared(F::Texel::to_raw(F::FAR), 1)],
            },
            light::widen,
        );
        let maps = RawMaps { format: cfg.format, maps };
        parts.push(LightPart { image, maps, truth, metrics, verdicts, light_events: events });
    }
    let first = parts.remove(0);
    let LightPart { image, maps, truth, metrics, verdicts, light_events } = first;
    let size = (image.width, image.height);
    let shadowless =
        scene.shadowless.iter().map(|l| reference.facing(&ids, &image.camera, size, &l.source())).collect();
    let render =
        Render { image, maps, truth, metrics, verdicts, light_events, camera_events, command, more: parts, shadowless };
    Ok((render, light_also))
}
