//! One render of a [`RenderConfig`]: the light pass for a shadow
//! algorithm, the camera pass, the exact reference and the metrics between
//! them ([`render`]); its cost on
//! architectures (`costed`); its pictures ([`pictures`]). This layer sits
//! above the passes, the cost model and the truth, and joins them.

pub mod arrays;
mod config;
mod costed;
pub mod files;
pub mod params;
pub mod pictures;
pub mod replay;
mod request;
pub(crate) mod shared;

use indicatif::ProgressBar;
use umbra_core::depth::Texel;
use umbra_core::shade::{MapUnit, SilhouetteUnit};
use umbra_core::shadow::{MapView, ShadowConfig, ShadowConfigError};
use umbra_core::silhouette::{Packed, SilPoint, SilStore, SilhouetteMap};
use umbra_core::{DepthFormat, DepthUnit, LightPassConfig, Probe, RasterConfig, TileState};

pub(crate) use self::config::Targets;
pub use self::config::{Checked, RenderConfig, RenderConfigError};
pub use self::costed::{cost, render_costed};
pub(crate) use self::costed::{cost_others, cost_unshadowed};
use self::replay::{PassInputs, judged};
pub use self::request::RenderRequest;
use crate::base::counters::Counters;
use crate::base::maps::{Tiling, with_format};
use crate::base::probes::Tee;
use crate::input::limits::LimitError;
use crate::pass::PassError;
use crate::pass::algorithm::MapKind;
pub(crate) use crate::pass::algorithm::{Algorithm, Culling};
use crate::pass::camera::{self, CameraFrame, CameraImage, CameraOptions, map_view, visibility, volumes};
use crate::pass::light::{self, DEFAULT_BIN_CAPACITY, LightFrame, LightMaps, LightOptions, RawMaps};
use crate::pass::occluders::silhouette_map;
use crate::truth::metrics::{Fields, Metrics, Verdict};
use crate::truth::reference::{PixelTruth, Reference, ReferenceError};
use crate::world::occluders::Occluders;
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
    /// measure (never a result of 0 % error).
    #[error("camera: the view shows no surface facing the light, so no pixel can be evaluated")]
    NothingEvaluated,
    /// The light's map receives no fragment: the light sees no object.
    #[error(transparent)]
    EmptyMap(#[from] crate::pass::light::EmptyMap),
}

/// Everything a render produced.
pub struct Render {
    /// The camera pass.
    pub image: CameraImage,
    /// The light pass's maps, raw bits.
    pub maps: RawMaps,
    /// The exact reference per pixel.
    pub truth: Vec<Option<PixelTruth>>,
    /// The render against the reference.
    pub metrics: Metrics,
    /// Each pixel's verdict, wrong ones by their cause.
    pub verdicts: Vec<Verdict>,
    /// Events of the light pass.
    pub light_events: Counters,
    /// Events of the camera pass.
    pub camera_events: Counters,
    /// The `umbra render` command line that renders it again, bit for bit
    /// ([`RenderConfig::command`]).
    pub command: String,
}

/// Where a render's exact reference comes from.
pub enum TruthSource<'p> {
    /// Built for this render, showing no progress.
    Quiet,
    /// Built for this render; the bar ticks once per reference row.
    Build(&'p ProgressBar),
    /// Built before ([`truth`]) for the same scene, image size and rays.
    Given(Vec<Option<PixelTruth>>),
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
    let none = (umbra_core::NoProbe, &mut umbra_core::NoProbe);
    Ok(with_format!(cfg.format, F => render_in::<F, _, _>(scene, cfg, checked, truth_from, none)?.0))
}

/// The reference `truth_from` names for the render's `image`, of the
/// configuration's image size: one built is cast through the triangles the
/// render's own camera pass saw (the visibility of [`truth`], bit for bit).
fn truth_of(
    cfg: &RenderConfig,
    truth_from: TruthSource<'_>,
    (ids, camera): (&[u32], umbra_core::glam::Mat4),
    (reference, light): (&Reference, &LightSource),
) -> Result<Vec<Option<PixelTruth>>, RenderError> {
    let build = |progress: &ProgressBar| {
        reference.image(ids, &camera, cfg.width, cfg.height, light, cfg.reference_rays, progress)
    };
    let truth = match truth_from {
        TruthSource::Quiet => build(&ProgressBar::hidden()),
        TruthSource::Build(progress) => build(progress),
        TruthSource::Given(t) => t,
    };
    if truth.len() as u64 != u64::from(cfg.width) * u64::from(cfg.height) {
        return Err(RenderError::Truth { width: cfg.width, height: cfg.height, found: truth.len() });
    }
    if !truth.iter().flatten().any(|t| t.faces_light) {
        return Err(RenderError::NothingEvaluated);
    }
    Ok(truth)
}

/// The exact reference of `scene` seen from its camera at `width × height`
/// with `samples²` rays per pixel (see [`Reference::image`]). It depends on
/// nothing else, so a sweep builds it once per scene and image.
///
/// # Errors
/// See [`RenderError`].
pub fn truth(
    scene: &Scene,
    width: u32,
    height: u32,
    samples: u32,
    progress: &ProgressBar,
) -> Result<Vec<Option<PixelTruth>>, RenderError> {
    let mut frame = CameraFrame::default();
    let vis = visibility(&mut frame, scene, (width, height), Tiling::DEFAULT, &mut umbra_core::NoProbe)?;
    let reference = Reference::of(scene)?;
    let light = scene.light().source();
    Ok(reference.image(frame.ids(), &vis.camera, width, height, &light, samples, progress))
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

/// The light pass and the camera pass of a render, reporting to the two
/// probes: the maps, the light probe and the camera image.
pub(super) fn passes<F: DepthFormat, L: Probe, C: Probe>(
    scene: &Scene,
    cfg: &RenderConfig,
    checked: Targets,
    frame: &mut LightFrame<F::Texel>,
    light_probe: L,
    camera_probe: &mut C,
    tiling: Tiling,
) -> Result<(L, CameraImage), RenderError> {
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let light_config = LightPassConfig { raster: checked.map, unit: units.unit, max_z_cull: true };
    let mut camera = CameraFrame::default();
    let size = (checked.image.width(), checked.image.height());
    if units.map == MapKind::Volumes {
        volumes(&mut camera, scene, size, tiling, camera_probe)?;
        return Ok((light_probe, camera.take_image()));
    }
    let draws = scene.draws_culled(scene.light().view_projection(), |solid| units.cull(solid, cfg.culling));
    let (maps, mut light_probe) = light::render::<F, _, DEFAULT_BIN_CAPACITY>(
        frame,
        light_config,
        &draws,
        LightOptions { per_draw: tiling.per_draw, ..LightOptions::default() },
        light_probe,
    )?;
    let options = camera_options(cfg, &units, size, tiling)?;
    let view = map_view::<F>(maps, units.front_culled)?;
    match units.map {
        MapKind::Silhouette { packed: true } => {
            silhouette::<Packed, F, _, _>(&mut camera, scene, &view, &options, &mut light_probe, camera_probe)?
        }
        MapKind::Silhouette { packed: false } => {
            silhouette::<SilPoint, F, _, _>(&mut camera, scene, &view, &options, &mut light_probe, camera_probe)?
        }
        MapKind::Depth | MapKind::Volumes => {
            camera::render(&mut camera, scene, &view, &MapUnit, &options, camera_probe)?
        }
    }
    Ok((light_probe, camera.take_image()))
}

/// The silhouette pass over the map (events to `light_probe`, as part of
/// the light side) and the camera pass with the silhouette unit.
fn silhouette<S: SilStore, F: DepthFormat, L: Probe, C: Probe>(
    frame: &mut CameraFrame,
    scene: &Scene,
    view: &MapView<'_, F>,
    options: &CameraOptions,
    light_probe: &mut L,
    camera_probe: &mut C,
) -> Result<(), RenderError> {
    let light = scene.light().view_projection();
    let texels = silhouette_map::<S, F, _>(&Occluders::new(scene), &light, view, options.shadow, light_probe)
        .map_err(PassError::from)?;
    let raster = view.raster();
    let sil = SilhouetteMap::view(raster.width(), raster.height(), &texels).map_err(PassError::from)?;
    camera::render(frame, scene, view, &SilhouetteUnit(&sil), options, camera_probe)?;
    Ok(())
}

/// The render of `cfg`, its events counted, and reporting to two more
/// probes besides (the architectures costed from the same passes).
pub(super) fn render_in<F: DepthFormat, L: Probe, C: Probe>(
    scene: &Scene,
    cfg: &RenderConfig,
    checked: Targets,
    truth_from: TruthSource<'_>,
    (light_also, camera_also): (L, &mut C),
) -> Result<(Render, L), RenderError> {
    let command = cfg.command(scene);
    let mut camera_events = Counters::new(&checked.image);
    let mut frame = LightFrame::new();
    let (Tee(light_events, light_also), image) = passes::<F, _, _>(
        scene,
        cfg,
        checked,
        &mut frame,
        Tee(Counters::new(&checked.map), light_also),
        &mut Tee(&mut camera_events, camera_also),
        Tiling::DEFAULT,
    )?;
    if frame.maps().is_some() {
        crate::pass::light::EmptyMap::check(&light_events.totals, "lights[0]")?;
    }
    let reference = Reference::of(scene)?;
    let ids: Vec<u32> = image.pixels.iter().map(|p| p.triangle).collect();
    let truth = truth_of(cfg, truth_from, (&ids, image.camera), (&reference, &scene.light().source()))?;
    let fields = Fields::new(&truth, image.width);
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let options = camera_options(cfg, &units, (image.width, image.height), Tiling::DEFAULT)?;
    let view = frame.maps().map(|maps| map_view::<F>(maps, units.front_culled)).transpose()?;
    let inputs =
        PassInputs { scene, seen: (&ids, image.camera), view: view.as_ref(), options: &options, kind: units.map };
    let (metrics, verdicts) = judged(&inputs, &image.pixels, (&truth, &fields, &reference))?;
    let maps = frame.maps().map_or_else(
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
    Ok((Render { image, maps, truth, metrics, verdicts, light_events, camera_events, command }, light_also))
}
