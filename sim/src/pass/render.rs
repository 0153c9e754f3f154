//! One render: the light pass for a shadow algorithm, the camera pass, the
//! exact reference and the metrics between them.

use indicatif::ProgressBar;
use serde::Serialize;
use umbra_core::shade::SilhouetteUnit;
use umbra_core::shadow::{Bias, DepthTest, Filter, ShadowConfig, ShadowConfigError};
use umbra_core::silhouette::{Packed, SilPoint, SilStore, SilhouetteMap};
use umbra_core::{
    CullMode, D16, D24, DepthFormat, DepthFormatKind, DepthUnit, F32, LightPassConfig, Probe, RasterConfig, TileState,
};

use crate::cost::arch::{ArchParams, ArchProbe, CostReport, Tee};
use crate::cost::counters::Counters;
use crate::io::limits::{LimitError, Limits};
use crate::pass::camera::{CameraImage, map_view, render_camera, render_camera_with, render_volumes, visibility};
use crate::pass::light::{LightError, LightMaps, RawMaps, render as light_render};
use crate::truth::metrics::{Metrics, compare};
use crate::truth::reference::{PixelTruth, Reference, ReferenceError};
use crate::world::occluders::{Occluders, silhouette_map};
use crate::world::scene::Scene;

/// A shadow algorithm of the four papers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Algorithm {
    /// Williams' first depth with a bias.
    First,
    /// First depth with Reeves et al.'s bias range: each sample's bias drawn
    /// uniformly from `[bias, hi]` (`Bias0`, `Bias1`; 1987 §3.2).
    BiasRange {
        /// `Bias1`, as a depth in `[0, 1]` (`Bias0` is the configuration's bias).
        hi: f64,
    },
    /// Wang & Molnar's second depth from the dual unit.
    Second,
    /// Second depth from front-face culling (solids culled, open surfaces not).
    SecondFrontCulled,
    /// Woo's midpoint of the dual unit.
    Midpoint,
    /// Weiskopf & Ertl's dual depth; solids back-face culled, open surfaces not.
    Dual {
        /// The largest distance above `z1`, as a depth in `[0, 1]`.
        offset: f64,
    },
    /// Sen, Cammarano & Hanrahan's silhouette map over a first-depth map
    /// (with the bias), decided by the skewed quadrants; no filter.
    Silhouette {
        /// Points packed to 4 bits per axis (one byte per texel) instead of
        /// 16 bits per axis.
        packed: bool,
    },
    /// Depth-fail stencil shadow volumes on the camera's raster: exact hard
    /// shadows, no light pass and no map.
    Volumes,
}

/// What to render and how.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RenderConfig {
    /// The shadow algorithm.
    pub algorithm: Algorithm,
    /// The map's depth format.
    #[serde(skip)]
    pub format: DepthFormatKind,
    /// The map's side in texels.
    pub map_size: u32,
    /// The filter.
    #[serde(skip)]
    pub filter: Filter,
    /// The bias, as a depth in `[0, 1]`.
    pub bias: f64,
    /// Wang & Molnar's virtual samples (second-depth algorithms).
    pub virtual_samples: bool,
    /// Camera image width.
    pub width: u32,
    /// Camera image height.
    pub height: u32,
    /// Reference rays per pixel side for the area-averaged visibility.
    pub reference_samples: u32,
}

/// Why a render failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The light or camera pass could not run.
    #[error(transparent)]
    Pass(#[from] LightError),
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
    /// The map, the image or the scene is beyond the [`Limits`].
    #[error(transparent)]
    Limit(#[from] LimitError),
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
    /// Events of the light pass.
    pub light_events: Counters,
    /// Events of the camera pass.
    pub camera_events: Counters,
}

/// Render `scene` with `cfg`; `progress` ticks once per reference row.
///
/// # Errors
/// See [`RenderError`].
pub fn render(scene: &Scene, cfg: &RenderConfig, progress: &ProgressBar) -> Result<Render, RenderError> {
    render_within(scene, cfg, &Limits::DEFAULT, progress)
}

/// [`render`] within `limits`: the map side, the image and the scene's
/// triangles are checked before any buffer is allocated.
///
/// # Errors
/// See [`RenderError`].
pub fn render_within(
    scene: &Scene,
    cfg: &RenderConfig,
    limits: &Limits,
    progress: &ProgressBar,
) -> Result<Render, RenderError> {
    check_limits(scene, cfg, limits)?;
    let truth = truth(scene, cfg.width, cfg.height, cfg.reference_samples, progress)?;
    render_checked(scene, cfg, truth)
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
    let (camera, ids) = visibility(scene, width, height, &mut umbra_core::NoProbe)?;
    let reference = Reference::new(&scene.triangles())?;
    let light = scene.light().source();
    Ok(reference.image(&ids, &camera, width, height, &light, samples, progress))
}

/// [`render_within`] against a reference [`truth`] built before, for the
/// same scene, image size and rays.
///
/// # Errors
/// See [`RenderError`].
pub fn render_against(
    scene: &Scene,
    cfg: &RenderConfig,
    truth: Vec<Option<PixelTruth>>,
    limits: &Limits,
) -> Result<Render, RenderError> {
    check_limits(scene, cfg, limits)?;
    render_checked(scene, cfg, truth)
}

/// Both passes of a render within limits already checked, against `truth`.
fn render_checked(scene: &Scene, cfg: &RenderConfig, truth: Vec<Option<PixelTruth>>) -> Result<Render, RenderError> {
    if truth.len() as u64 != u64::from(cfg.width) * u64::from(cfg.height) {
        return Err(RenderError::Truth { width: cfg.width, height: cfg.height, found: truth.len() });
    }
    match cfg.format {
        DepthFormatKind::D16 => render_in::<D16>(scene, cfg, truth),
        DepthFormatKind::D24 => render_in::<D24>(scene, cfg, truth),
        DepthFormatKind::F32 => render_in::<F32>(scene, cfg, truth),
    }
}

/// The map side, the image size and the scene's triangles against `limits`.
fn check_limits(scene: &Scene, cfg: &RenderConfig, limits: &Limits) -> Result<(), LimitError> {
    limits.check_map(cfg.map_size)?;
    limits.check_image(cfg.width, cfg.height)?;
    let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
    limits.check_triangles(u64::try_from(triangles).unwrap_or(u64::MAX))
}

/// The light pass (tiles of `tile` pixels) and the camera pass of a render,
/// reporting to the two probes.
fn passes<F: DepthFormat, L: Probe, C: Probe>(
    scene: &Scene,
    cfg: &RenderConfig,
    tile: u32,
    light_probe: L,
    camera_probe: &mut C,
) -> Result<(LightMaps<F::Texel>, L, CameraImage), RenderError> {
    if cfg.algorithm == Algorithm::Volumes {
        RasterConfig::new(cfg.width, cfg.height, RasterConfig::DEFAULT_TILE_SIZE, 8).map_err(RenderError::ImageSize)?;
        let image = render_volumes(scene, cfg.width, cfg.height, camera_probe)?;
        let raster = RasterConfig::new(1, 1, RasterConfig::DEFAULT_TILE_SIZE, 8).map_err(RenderError::MapSize)?;
        let none = LightMaps {
            config: LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true },
            z1: vec![F::FAR],
            z2: Vec::new(),
            tiles: vec![TileState::cleared(F::FAR, 1)],
        };
        return Ok((none, light_probe, image));
    }
    let unit = unit_of(cfg.algorithm);
    let (front_culled, test) = match cfg.algorithm {
        Algorithm::First | Algorithm::BiasRange { .. } | Algorithm::Silhouette { .. } | Algorithm::Volumes => {
            (false, DepthTest::First)
        }
        Algorithm::Second => (false, DepthTest::Second),
        Algorithm::SecondFrontCulled => (true, DepthTest::Second),
        Algorithm::Midpoint => (false, DepthTest::Midpoint),
        Algorithm::Dual { offset } => (false, DepthTest::Dual { offset: F::plane_z(offset) }),
    };
    let cull = |solid: bool| match (cfg.algorithm, solid) {
        (Algorithm::SecondFrontCulled, true) => CullMode::Front,
        (Algorithm::Dual { .. }, true) => CullMode::Back,
        _ => CullMode::None,
    };
    let raster = RasterConfig::new(cfg.map_size, cfg.map_size, tile, 8).map_err(RenderError::MapSize)?;
    let light_config = LightPassConfig { raster, unit, max_z_cull: true };
    let draws = scene.draws_culled(scene.light().view_projection(), cull);
    let (maps, mut light_probe) = light_render::<F, _>(light_config, &draws, light_probe)?;
    let bias = match cfg.algorithm {
        Algorithm::BiasRange { hi } => Bias::Range { lo: F::plane_z(cfg.bias), hi: F::plane_z(hi) },
        _ => Bias::Constant(F::plane_z(cfg.bias)),
    };
    let shadow = ShadowConfig::new(test, bias, cfg.filter, true)?;
    RasterConfig::new(cfg.width, cfg.height, RasterConfig::DEFAULT_TILE_SIZE, 8).map_err(RenderError::ImageSize)?;
    let virtual_samples = cfg.virtual_samples && test == DepthTest::Second;
    if let Algorithm::Silhouette { packed } = cfg.algorithm {
        let image = if packed {
            silhouette_image::<Packed, F, _, _>(scene, cfg, &maps, shadow, &mut light_probe, camera_probe)?
        } else {
            silhouette_image::<SilPoint, F, _, _>(scene, cfg, &maps, shadow, &mut light_probe, camera_probe)?
        };
        return Ok((maps, light_probe, image));
    }
    let image = render_camera::<F, _>(
        scene,
        &maps,
        front_culled,
        shadow,
        virtual_samples,
        cfg.width,
        cfg.height,
        camera_probe,
    )?;
    Ok((maps, light_probe, image))
}

/// The silhouette pass over `maps` (events to `light_probe`, as part of
/// the light side) and the camera pass with the silhouette unit.
fn silhouette_image<S: SilStore, F: DepthFormat, L: Probe, C: Probe>(
    scene: &Scene,
    cfg: &RenderConfig,
    maps: &LightMaps<F::Texel>,
    shadow: ShadowConfig,
    light_probe: &mut L,
    camera_probe: &mut C,
) -> Result<CameraImage, LightError> {
    let view = map_view::<F>(maps, false)?;
    let light = scene.light().view_projection();
    let texels = silhouette_map::<S, F, _>(&Occluders::new(scene), &light, &view, shadow, light_probe)?;
    let sil = SilhouetteMap::view(cfg.map_size, cfg.map_size, &texels)?;
    render_camera_with(scene, &view, shadow, false, cfg.width, cfg.height, &SilhouetteUnit(&sil), camera_probe)
}

/// The light pass's unit for an algorithm.
const fn unit_of(a: Algorithm) -> DepthUnit {
    match a {
        Algorithm::First
        | Algorithm::BiasRange { .. }
        | Algorithm::SecondFrontCulled
        | Algorithm::Silhouette { .. }
        | Algorithm::Volumes => DepthUnit::Single,
        _ => DepthUnit::Dual,
    }
}

fn render_in<F: DepthFormat>(
    scene: &Scene,
    cfg: &RenderConfig,
    truth: Vec<Option<PixelTruth>>,
) -> Result<Render, RenderError> {
    let map_raster = RasterConfig::new(cfg.map_size, cfg.map_size, RasterConfig::DEFAULT_TILE_SIZE, 8)
        .map_err(RenderError::MapSize)?;
    let camera_raster =
        RasterConfig::new(cfg.width, cfg.height, RasterConfig::DEFAULT_TILE_SIZE, 8).map_err(RenderError::ImageSize)?;
    let mut camera_events = Counters::new(&camera_raster);
    let (maps, light_events, image) =
        passes::<F, _, _>(scene, cfg, RasterConfig::DEFAULT_TILE_SIZE, Counters::new(&map_raster), &mut camera_events)?;
    let metrics = compare(&image.pixels, &truth);
    let maps = RawMaps { format: cfg.format, maps: crate::pass::light::widen(maps) };
    Ok(Render { image, maps, truth, metrics, light_events, camera_events })
}

/// The cost of a render on an architecture: both passes through its model.
/// Returns the report and the light pass's probe (for the timeline).
///
/// # Errors
/// See [`RenderError`].
pub fn cost(scene: &Scene, cfg: &RenderConfig, arch: ArchParams) -> Result<(CostReport, ArchProbe), RenderError> {
    cost_within(scene, cfg, arch, &Limits::DEFAULT)
}

/// [`cost`] within `limits`, checked as [`render_within`] checks them.
///
/// # Errors
/// See [`RenderError`].
pub fn cost_within(
    scene: &Scene,
    cfg: &RenderConfig,
    arch: ArchParams,
    limits: &Limits,
) -> Result<(CostReport, ArchProbe), RenderError> {
    check_limits(scene, cfg, limits)?;
    match cfg.format {
        DepthFormatKind::D16 => cost_in::<D16>(scene, cfg, arch),
        DepthFormatKind::D24 => cost_in::<D24>(scene, cfg, arch),
        DepthFormatKind::F32 => cost_in::<F32>(scene, cfg, arch),
    }
}

fn cost_in<F: DepthFormat>(
    scene: &Scene,
    cfg: &RenderConfig,
    arch: ArchParams,
) -> Result<(CostReport, ArchProbe), RenderError> {
    let unit = unit_of(cfg.algorithm);
    let light = ArchProbe::new(arch, cfg.format, unit).with_timeline();
    let camera = ArchProbe::new(arch, cfg.format, DepthUnit::Single);
    let (camera, light, image, fetched) = if let Some((size, line, ways)) = arch.map_cache {
        let cache = crate::cost::cache::Cache::new(size, line, ways).map_err(|e| RenderError::Cache(e.to_string()))?;
        let sil =
            if let Algorithm::Silhouette { packed: true } = cfg.algorithm { Packed::BYTES } else { SilPoint::BYTES };
        let map = crate::cost::cache::MapCache::new(cache, unit.buffers(), cfg.format.bytes()).with_silhouette(sil);
        let mut probe = Tee(camera, map);
        let (_, light, image) = passes::<F, _, _>(scene, cfg, arch.tile, light, &mut probe)?;
        let fetched = probe.1.cache.fetched_bytes();
        (probe.0, light, image, Some(fetched))
    } else {
        let mut camera = camera;
        let (_, light, image) = passes::<F, _, _>(scene, cfg, arch.tile, light, &mut camera)?;
        (camera, light, image, None)
    };
    let pixels = image.pixels.iter().filter(|p| p.triangle != umbra_core::NO_TRIANGLE).count() as u64;
    let samples = match cfg.filter {
        Filter::Point => 1,
        Filter::Bilinear => 4,
        Filter::Box { size } => u64::from(size) * u64::from(size),
        Filter::Jittered(j) => u64::from(j.num_samples),
    };
    Ok((CostReport::new(&light, &camera, fetched, pixels, samples), light))
}
