//! One render: the light pass for a shadow algorithm, the camera pass, the
//! exact reference and the metrics between them ([`render`]); its cost on
//! architectures ([`costed`]); its pictures ([`pictures`]). This layer sits
//! above the passes, the cost model and the truth, and joins them.

pub mod arrays;
pub mod costed;
pub mod pictures;
pub mod shared;

use indicatif::ProgressBar;
use serde::Serialize;
use umbra_core::depth::Texel;
use umbra_core::shade::{MapUnit, SilhouetteUnit};
use umbra_core::shadow::{Filter, MapView, ShadowConfig, ShadowConfigError};
use umbra_core::silhouette::{Packed, SilPoint, SilStore, SilhouetteMap};
use umbra_core::{DepthFormat, DepthFormatKind, DepthUnit, LightPassConfig, Probe, RasterConfig, TileState};

pub use self::costed::{cost, cost_others, cost_unshadowed, render_costed};
use crate::base::counters::Counters;
use crate::base::maps::{Tiling, with_format};
use crate::base::probes::Tee;
use crate::io::limits::{Footprint, LimitError, Limits};
use crate::pass::PassError;
use crate::pass::algorithm::MapKind;
pub use crate::pass::algorithm::{Algorithm, Cull, Culling};
use crate::pass::camera::{self, CameraFrame, CameraImage, CameraOptions, map_view, visibility, volumes};
use crate::pass::light::{self, DEFAULT_BIN_CAPACITY, LightFrame, LightMaps, LightOptions, RawMaps};
use crate::pass::occluders::silhouette_map;
use crate::truth::metrics::{Metrics, compare};
use crate::truth::reference::{PixelTruth, Reference, ReferenceError};
use crate::world::occluders::Occluders;
use crate::world::scene::Scene;

/// What to render and how.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RenderConfig {
    /// The shadow algorithm (written as `--algo` spells it; a dual offset
    /// or a bias range's end is in the render command).
    #[serde(serialize_with = "crate::base::text::serialize")]
    pub algorithm: Algorithm,
    /// The map's depth format.
    #[serde(serialize_with = "crate::base::text::serialize")]
    pub format: DepthFormatKind,
    /// The map's side in texels.
    pub map_size: u32,
    /// The filter.
    #[serde(serialize_with = "crate::base::text::serialize")]
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
    pub reference_rays: u32,
    /// The light pass's culling per object class.
    #[serde(serialize_with = "crate::base::text::serialize")]
    pub culling: Culling,
}

/// A render configuration no render takes, naming the quantity and the value.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RenderConfigError {
    /// A bias, `Bias1` or dual offset outside `[0, 1]` (or not a number).
    #[error("{quantity} {value} is not a depth in [0, 1]")]
    Depth {
        /// `bias`, `bias1` or `offset`.
        quantity: &'static str,
        /// The value given.
        value: f64,
    },
    /// Reference rays per pixel side outside `1..=16`.
    #[error("reference_rays {0} is outside 1..=16")]
    ReferenceRays(u32),
    /// A map side or image side of zero.
    #[error("{quantity} is 0: it must be at least 1")]
    Zero {
        /// `map_size`, `width` or `height`.
        quantity: &'static str,
    },
}

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

/// A render configuration checked once: its map and camera targets.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Checked {
    /// The light pass's target (the map).
    pub(super) map: RasterConfig,
    /// The camera pass's target (the image).
    pub(super) image: RasterConfig,
}

impl RenderConfig {
    /// The default render (`umbra render`'s): Wang & Molnar's second depth
    /// with virtual samples, a 24-bit 1024² map, bilinear filtering, no
    /// bias, the algorithm's culling, 960×540 against 4² reference rays a
    /// pixel. Change fields with struct update syntax, then [`checked`](Self::checked).
    pub const DEFAULT: Self = Self {
        algorithm: Algorithm::Second,
        format: DepthFormatKind::D24,
        map_size: 1024,
        filter: Filter::Bilinear,
        bias: 0.0,
        virtual_samples: true,
        width: 960,
        height: 540,
        reference_rays: 4,
        culling: Culling::ALGORITHM,
    };

    /// Reference rays per pixel side a render takes.
    pub const REFERENCE_RAYS: std::ops::RangeInclusive<u32> = 1..=16;

    /// `value` if it is a depth in `[0, 1]`, for the quantity named.
    ///
    /// # Errors
    /// [`RenderConfigError::Depth`].
    pub fn depth(quantity: &'static str, value: f64) -> Result<f64, RenderConfigError> {
        if value.is_finite() && (0.0..=1.0).contains(&value) {
            Ok(value)
        } else {
            Err(RenderConfigError::Depth { quantity, value })
        }
    }

    /// The configuration, if a render takes it: every bias and offset a
    /// depth in `[0, 1]`, 1 to 16 reference rays a side, no side of zero.
    /// (Sizes against a machine's [`Limits`] and the filter against the
    /// shadow unit are checked when the render starts.) Every render
    /// checks this first; the command line and sweep files call it to
    /// report a mistake before anything runs.
    ///
    /// ```
    /// use umbra_sim::render::{Algorithm, RenderConfig, RenderConfigError};
    /// let first = RenderConfig { algorithm: Algorithm::First, bias: 0.002, ..RenderConfig::DEFAULT };
    /// assert!(first.checked().is_ok());
    /// let bad = RenderConfig { bias: 1.5, ..first };
    /// assert_eq!(bad.checked(), Err(RenderConfigError::Depth { quantity: "bias", value: 1.5 }));
    /// ```
    ///
    /// # Errors
    /// [`RenderConfigError`] naming the first quantity out of range.
    pub fn checked(self) -> Result<Self, RenderConfigError> {
        Self::depth("bias", self.bias)?;
        if let Some(hi) = self.algorithm.bias_hi() {
            Self::depth("bias1", hi)?;
        }
        if let Some(offset) = self.algorithm.offset() {
            Self::depth("offset", offset)?;
        }
        if !Self::REFERENCE_RAYS.contains(&self.reference_rays) {
            return Err(RenderConfigError::ReferenceRays(self.reference_rays));
        }
        for (quantity, side) in [("map_size", self.map_size), ("width", self.width), ("height", self.height)] {
            if side == 0 {
                return Err(RenderConfigError::Zero { quantity });
            }
        }
        Ok(self)
    }

    /// The configuration in words, every field (for the records outputs carry).
    #[must_use]
    pub fn describe(&self) -> String {
        format!(
            "{}, {}, map {}², filter {}, bias {}, virtual samples {}, culling {}, image {}x{}, {}² reference rays",
            self.algorithm.flags().trim_start_matches("--algo "),
            self.format.name(),
            self.map_size,
            self.filter,
            self.bias,
            self.virtual_samples,
            self.culling,
            self.width,
            self.height,
            self.reference_rays
        )
    }

    /// The `umbra render` command line that renders this configuration of
    /// the scene `source` (a bundled name or a file) again, bit for bit.
    #[must_use]
    pub fn command(&self, source: &str) -> String {
        let quoted = crate::io::provenance::shell_word(source);
        let mut c = format!(
            "umbra render {quoted} {} --depth {} --map {} --filter {} --bias {} --width {} --height {} --reference-rays {}",
            self.algorithm.flags(),
            self.format.name(),
            self.map_size,
            self.filter,
            self.bias,
            self.width,
            self.height,
            self.reference_rays
        );
        if !self.virtual_samples {
            c.push_str(" --no-virtual-samples");
        }
        if self.culling != Culling::ALGORITHM {
            c.push_str(&format!(" --cull {}", self.culling));
        }
        c
    }

    /// Whether a render of `scene` with this configuration is within
    /// `limits` (the map, the image, the triangles and the memory all
    /// together, [`Footprint::render`]): the check [`render`] makes before
    /// it allocates, for a caller to make before it writes anything.
    ///
    /// # Errors
    /// [`RenderError`] naming the first quantity beyond its limit.
    pub fn within(&self, scene: &Scene, limits: &Limits) -> Result<(), RenderError> {
        self.check(scene, limits, RasterConfig::DEFAULT_TILE_SIZE).map(|_| ())
    }

    /// Check the map side, the image size and the scene's triangles against
    /// `limits`, before any buffer is allocated, and the targets the passes
    /// will draw, both in `tile`-pixel tiles.
    pub(crate) fn check(&self, scene: &Scene, limits: &Limits, tile: u32) -> Result<Checked, RenderError> {
        self.checked()?;
        limits.check_map(self.map_size)?;
        limits.check_image(self.width, self.height)?;
        let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
        let triangles = u64::try_from(triangles).unwrap_or(u64::MAX);
        limits.check_triangles(triangles)?;
        let pixels = u64::from(self.width) * u64::from(self.height);
        limits.check_memory("the render", Footprint::render(pixels, self.map_size, triangles))?;
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
/// ```
/// use umbra_sim::{Limits, RenderConfig, Scene, TruthSource};
/// let scene = Scene::open("weiskopf-l", &Limits::DEFAULT)?;
/// let cfg = RenderConfig { width: 96, height: 72, map_size: 128, ..RenderConfig::DEFAULT };
/// let r = umbra_sim::render(&scene, &cfg, &Limits::DEFAULT, TruthSource::Quiet)?;
/// let m = &r.metrics;
/// assert_eq!(m.evaluated as usize, r.truth.iter().flatten().filter(|t| t.faces_light).count());
/// assert!(m.edge_placement + m.acne + m.leaks <= m.evaluated);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
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
    let none = (umbra_core::NoProbe, &mut umbra_core::NoProbe);
    Ok(with_format!(cfg.format, F => render_in::<F, _, _>(scene, cfg, checked, truth_from, none)?.0))
}

/// The reference `truth_from` names for the render's `image`, of the
/// configuration's image size: one built is cast through the triangles the
/// render's own camera pass saw (the visibility of [`truth`], bit for bit).
fn truth_of(
    scene: &Scene,
    cfg: &RenderConfig,
    truth_from: TruthSource<'_>,
    image: &CameraImage,
) -> Result<Vec<Option<PixelTruth>>, RenderError> {
    let build = |progress: &ProgressBar| -> Result<_, RenderError> {
        let ids: Vec<u32> = image.pixels.iter().map(|p| p.triangle).collect();
        let light = scene.light().source();
        let reference = Reference::new(&scene.triangles())?;
        Ok(reference.image(&ids, &image.camera, cfg.width, cfg.height, &light, cfg.reference_rays, progress))
    };
    let truth = match truth_from {
        TruthSource::Quiet => build(&ProgressBar::hidden())?,
        TruthSource::Build(progress) => build(progress)?,
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
    truth_from: TruthSource<'_>,
    (light_also, camera_also): (L, &mut C),
) -> Result<(Render, L), RenderError> {
    let command = cfg.command(&scene.source);
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
    let truth = truth_of(scene, cfg, truth_from, &image)?;
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
    Ok((Render { image, maps, truth, metrics, light_events, camera_events, command }, light_also))
}
