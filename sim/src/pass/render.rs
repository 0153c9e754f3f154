//! One render: the light pass for a shadow algorithm, the camera pass, the
//! exact reference and the metrics between them.

use indicatif::ProgressBar;
use serde::Serialize;
use umbra_core::depth::Texel;
use umbra_core::shade::{MapUnit, SilhouetteUnit};
use umbra_core::shadow::{Filter, MapView, ShadowConfig, ShadowConfigError};
use umbra_core::silhouette::{Packed, SilPoint, SilStore, SilhouetteMap};
use umbra_core::{
    D16, D24, DepthFormat, DepthFormatKind, DepthUnit, F32, LightPassConfig, Probe, RasterConfig, TileState,
};

use super::PassError;
use super::algorithm::MapKind;
pub use super::algorithm::{Algorithm, Cull, Culling};
use super::camera::{self, CameraFrame, CameraImage, CameraOptions, Tiling, map_view, visibility, volumes};
pub use super::costed::{Fan, cost, cost_unshadowed, render_costed};
use super::light::{self, DEFAULT_BIN_CAPACITY, LightFrame, LightMaps, LightOptions, RawMaps};
use crate::cost::arch::Tee;
use crate::cost::counters::Counters;
use crate::io::limits::{LimitError, Limits};
use crate::truth::metrics::{Metrics, compare};
use crate::truth::reference::{PixelTruth, Reference, ReferenceError};
use crate::world::occluders::{Occluders, silhouette_map};
use crate::world::scene::Scene;

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
    /// The light pass's culling per object class.
    pub culling: Culling,
}

/// Why a render failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
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
    /// The map, the image or the scene is beyond the [`Limits`].
    #[error(transparent)]
    Limit(#[from] LimitError),
    /// The camera sees no surface facing the light: there is no pixel to
    /// measure (never a result of 0 % error).
    #[error("camera: the view shows no surface facing the light, so no pixel can be evaluated")]
    NothingEvaluated,
    /// The light's map receives no fragment: the light sees no object.
    #[error("lights[0]: the light's map receives no fragment: no triangle lies in its view between near and far")]
    EmptyMap,
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

/// Where a render's exact reference comes from.
pub enum TruthSource<'p> {
    /// Built for this render; the bar ticks once per reference row.
    Build(&'p ProgressBar),
    /// Built before ([`truth`]) for the same scene, image size and rays.
    Given(Vec<Option<PixelTruth>>),
}

/// A render configuration checked once: its map and camera targets.
#[derive(Clone, Copy, Debug)]
pub(super) struct Checked {
    /// The light pass's target (the map).
    pub(super) map: RasterConfig,
    /// The camera pass's target (the image).
    pub(super) image: RasterConfig,
}

impl RenderConfig {
    /// The configuration in words, every field (for the records outputs carry).
    #[must_use]
    pub fn describe(&self) -> String {
        format!(
            "{}, {}, map {}², filter {:?}, bias {}, virtual samples {}, culling {}, image {}x{}, {}² reference rays",
            self.algorithm.flags().trim_start_matches("--algo "),
            self.format.name(),
            self.map_size,
            self.filter,
            self.bias,
            self.virtual_samples,
            self.culling.label(),
            self.width,
            self.height,
            self.reference_samples
        )
    }

    /// The `umbra render` command line that renders this configuration of
    /// the scene `source` (a bundled name or a file) again, bit for bit.
    #[must_use]
    pub fn command(&self, source: &str) -> String {
        let filter = match self.filter {
            Filter::Point => "point".to_owned(),
            Filter::Bilinear => "bilinear".to_owned(),
            Filter::Box { size } => format!("box{size}"),
            Filter::Jittered(j) => format!(
                "jitter --num-samples {} --res-factor {} --min-samples {} --min-size {}",
                j.num_samples, j.res_factor, j.min_samples, j.min_size
            ),
        };
        let quoted = crate::io::provenance::shell_word(source);
        let mut c = format!(
            "umbra render {quoted} {} --depth {} --map {} --filter {filter} --bias {} --width {} --height {} --reference-samples {}",
            self.algorithm.flags(),
            self.format.name(),
            self.map_size,
            self.bias,
            self.width,
            self.height,
            self.reference_samples
        );
        if !self.virtual_samples {
            c.push_str(" --no-virtual-samples");
        }
        if self.culling != Culling::ALGORITHM {
            c.push_str(&format!(" --cull {}", self.culling.label()));
        }
        c
    }

    /// Check the map side, the image size and the scene's triangles against
    /// `limits`, before any buffer is allocated, and the targets the passes
    /// will draw, both in `tile`-pixel tiles.
    pub(super) fn check(&self, scene: &Scene, limits: &Limits, tile: u32) -> Result<Checked, RenderError> {
        limits.check_map(self.map_size)?;
        limits.check_image(self.width, self.height)?;
        let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
        limits.check_triangles(u64::try_from(triangles).unwrap_or(u64::MAX))?;
        let bits = RasterConfig::DEFAULT_SUBPIXEL_BITS;
        let image = RasterConfig::new(self.width, self.height, tile, bits).map_err(RenderError::ImageSize)?;
        // Shadow volumes draw no map: one texel stands for it.
        let side = if self.algorithm == Algorithm::Volumes { 1 } else { self.map_size };
        let map = RasterConfig::new(side, side, tile, bits).map_err(RenderError::MapSize)?;
        Ok(Checked { map, image })
    }
}

/// Render `scene` with `cfg` within `limits`, against the exact reference
/// `truth` names.
///
/// # Errors
/// See [`RenderError`].
pub fn render(
    scene: &Scene,
    cfg: &RenderConfig,
    limits: &Limits,
    truth_from: TruthSource<'_>,
) -> Result<Render, RenderError> {
    let checked = cfg.check(scene, limits, RasterConfig::DEFAULT_TILE_SIZE)?;
    let truth = truth_of(scene, cfg, truth_from)?;
    let none = (umbra_core::NoProbe, &mut umbra_core::NoProbe);
    Ok(match cfg.format {
        DepthFormatKind::D16 => render_in::<D16, _, _>(scene, cfg, checked, truth, none)?.0,
        DepthFormatKind::D24 => render_in::<D24, _, _>(scene, cfg, checked, truth, none)?.0,
        DepthFormatKind::F32 => render_in::<F32, _, _>(scene, cfg, checked, truth, none)?.0,
    })
}

/// The reference `truth_from` names, of the configuration's image size.
pub(super) fn truth_of(
    scene: &Scene,
    cfg: &RenderConfig,
    truth_from: TruthSource<'_>,
) -> Result<Vec<Option<PixelTruth>>, RenderError> {
    let truth = match truth_from {
        TruthSource::Build(progress) => truth(scene, cfg.width, cfg.height, cfg.reference_samples, progress)?,
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
    let reference = Reference::new(&scene.triangles())?;
    let light = scene.light().source();
    Ok(reference.image(frame.ids(), &vis.camera, width, height, &light, samples, progress))
}

/// The light pass and the camera pass of a render, reporting to the two
/// probes: the maps, the light probe and the camera image.
pub(super) fn passes<F: DepthFormat, L: Probe, C: Probe>(
    scene: &Scene,
    cfg: &RenderConfig,
    checked: Checked,
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
    let options = CameraOptions {
        width: size.0,
        height: size.1,
        shadow: ShadowConfig::new(units.test, units.bias, cfg.filter, true)?,
        virtual_samples: units.virtual_samples(cfg.virtual_samples),
        tiling,
    };
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
    checked: Checked,
    truth: Vec<Option<PixelTruth>>,
    (light_also, camera_also): (L, &mut C),
) -> Result<(Render, L), RenderError> {
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
    if frame.maps().is_some() && light_events.totals.setups == 0 {
        return Err(RenderError::EmptyMap);
    }
    let metrics = compare(&image.pixels, &truth, image.width);
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
    Ok((Render { image, maps, truth, metrics, light_events, camera_events }, light_also))
}
