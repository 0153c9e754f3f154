//! A render's passes: a light pass per map (one a shadow-casting light,
//! or one a cascade of a cascaded directional light), then the camera
//! pass: the visibility unit once, the shading unit once per map over
//! the pixels that read it, a cascaded light's cascades put together per
//! pixel ([`crate::pass::cascade`]).

use umbra_core::glam::Mat4;
use umbra_core::shade::{MapUnit, ShadowUnit, SilhouetteUnit};
use umbra_core::shadow::MapView;
use umbra_core::silhouette::SilStore;
use umbra_core::{DepthFormat, LightPassConfig, Probe, RasterConfig};

use super::{RenderConfig, RenderError, Targets, camera_options};
use crate::base::maps::Tiling;
use crate::pass::PassError;
use crate::pass::algorithm::MapKind;
use crate::pass::camera::{CameraFrame, CameraImage, CameraOptions, map_view, shade_visible, visibility, volumes};
use crate::pass::cascade::{Picks, Plan, Seen, shade_cascades};
use crate::pass::light::{self, DEFAULT_BIN_CAPACITY, LightFrame, LightOptions};
use crate::pass::occluders::{SilReader, SilReaderAll, SilTexels};
use crate::world::occluders::Lit;
use crate::world::scene::{Light, Scene};

/// One map a render draws: light `light`'s, or cascade `cascade` of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MapSlot {
    /// The shadow-casting light, by index.
    pub(crate) light: usize,
    /// Its cascade (`0` for a light of one map).
    pub(crate) cascade: usize,
    /// The map's target.
    pub(crate) raster: RasterConfig,
}

impl MapSlot {
    /// The map's name in files and messages: `lights[k]`, and
    /// `lights[k].cascades[c]` for a cascade.
    #[must_use]
    pub(crate) fn key(&self, cascaded: bool) -> String {
        let light = Scene::light_key(self.light);
        if cascaded { format!("{light}.cascades[{}]", self.cascade) } else { light }
    }
}

/// The maps a render of `cfg` draws of `scene`, in tiles of the map
/// target `map`'s: one per shadow-casting light (one for a scene of
/// none, or for shadow volumes), a cascaded light's one per cascade at
/// its side.
///
/// # Errors
/// [`RenderError::MapSize`] for a cascade's side the core refuses.
pub(crate) fn map_slots(scene: &Scene, cfg: &RenderConfig, map: RasterConfig) -> Result<Vec<MapSlot>, RenderError> {
    let mut slots = Vec::new();
    for light in 0..scene.lights.len().max(1) {
        let cascades = cfg.cascades_of(scene, light);
        if !cascades.cascaded() {
            slots.push(MapSlot { light, cascade: 0, raster: map });
            continue;
        }
        for cascade in 0..cascades.count() {
            let side = cascades.side(cascade, cfg.map_size);
            let raster =
                RasterConfig::new(side, side, map.tile_size(), map.subpixel_bits()).map_err(RenderError::MapSize)?;
            slots.push(MapSlot { light, cascade, raster });
        }
    }
    Ok(slots)
}

/// Tell `probe` that the shadow unit reads map `m` of `maps`, when the
/// pass reads more than one.
fn bind<P: Probe>(probe: &mut P, m: usize, maps: usize) {
    if maps > 1 {
        probe.map_bound(u16::try_from(m).unwrap_or(u16::MAX));
    }
}

/// What a render's passes leave ([`passes`]).
pub(super) struct Passes<L> {
    /// The light probes, one a map.
    pub(super) light_probes: Vec<L>,
    /// One camera image a light, a cascaded light's cascades put together.
    pub(super) images: Vec<CameraImage>,
    /// Each map's silhouette map, for an algorithm that draws one.
    pub(super) silhouettes: Vec<SilTexels>,
    /// The scene's triangles ([`Scene::triangles`]), as the shading read them.
    pub(super) triangles: Vec<umbra_core::shade::SceneTriangle>,
    /// The light each map was drawn through (a cascade's, fitted).
    pub(super) drawn: Vec<Light>,
    /// Each light's cascades, planned for the view, each pixel's cascade,
    /// and, where blend bands mix two cascades, each pixel as its own
    /// cascade shaded it; `None` for a light of one map.
    pub(super) plans: Vec<Option<Cascaded>>,
}

/// A cascaded light's plan, each pixel's cascade, and each pixel as its
/// own cascade shaded it where blend bands mix two (`None` otherwise).
pub(super) type Cascaded = (Plan, Vec<u8>, Option<Vec<umbra_core::shade::Shaded>>);

/// The passes of a render of `scene`, lit by each of its lights as `lit`
/// holds it ([`Lit::each`]), drawing the maps `slots` ([`map_slots`]):
/// the visibility unit, then a light pass per map, each reporting to its
/// own of `light_probes` and drawing into its own of `frames` (with its
/// silhouette pass, for a silhouette map), then the shading unit once per
/// map over the pixels that read it (the probe told which map it reads),
/// or the stencil unit once per light for shadow volumes. The light
/// probes, one camera image per light, and each map's silhouette map
/// (none for other algorithms), for the judge to read.
#[allow(clippy::too_many_arguments, reason = "the scene, the configuration, the targets and the probes")]
pub(super) fn passes<F: DepthFormat, L: Probe, C: Probe>(
    (scene, lit): (&Scene, &[Lit<'_>]),
    cfg: &RenderConfig,
    (checked, slots): (Targets, &[MapSlot]),
    frames: &mut Vec<LightFrame<F::Texel>>,
    light_probes: Vec<L>,
    camera_probe: &mut C,
    tiling: Tiling,
) -> Result<Passes<L>, RenderError> {
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let mut camera = CameraFrame::default();
    let size = (checked.image.width(), checked.image.height());
    debug_assert_eq!(light_probes.len(), slots.len(), "one light probe per map");
    let triangles = scene.triangles();
    if units.map == MapKind::Volumes {
        let images = volumes(&mut camera, (scene, &triangles, lit), size, tiling, camera_probe)?;
        let drawn = lit.iter().map(|l| l.scene.light()).collect();
        let plans = lit.iter().map(|_| None).collect();
        return Ok(Passes { light_probes, images, silhouettes: Vec::new(), triangles, drawn, plans });
    }
    let vis = visibility(&mut camera, scene, size, tiling, camera_probe)?;
    let seen = Seen { camera: vis.camera, size, depth: camera.depth(), ids: camera.ids() };
    let mut plans = Vec::with_capacity(lit.len());
    for (k, one) in lit.iter().enumerate() {
        plans.push(match one.scene.light() {
            Light::Directional(view, _) if cfg.cascades_of(scene, k).cascaded() => {
                let plan = Plan::new((&view, &cfg.cascades_of(scene, k)), &scene.camera, &seen, cfg.map_size)?;
                let picks = Picks::new(&plan.select, &seen);
                Some((plan, picks))
            }
            _ => None,
        });
    }
    let drawn: Vec<Light> = slots
        .iter()
        .map(|s| match &plans[s.light] {
            Some((plan, _)) => plan.lights[s.cascade],
            None => lit[s.light].scene.light(),
        })
        .collect();
    frames.resize_with(slots.len(), LightFrame::new);
    let drawing = LightOptions { per_draw: tiling.per_draw, ..LightOptions::default() };
    let mut views = Vec::with_capacity(slots.len());
    let mut probes = Vec::with_capacity(slots.len());
    for (((slot, light), frame), probe) in slots.iter().zip(&drawn).zip(frames.iter_mut()).zip(light_probes) {
        let one = &lit[slot.light].scene;
        let draws = one.draws_culled(light.view_projection(), |solid| units.cull(solid, cfg.culling));
        let light_config = LightPassConfig { raster: slot.raster, unit: units.unit, max_z_cull: true };
        let (maps, probe) = light::render::<F, _, DEFAULT_BIN_CAPACITY>(frame, light_config, &draws, drawing, probe)?;
        views.push(map_view::<F>(maps, units.front_culled)?);
        probes.push(probe);
    }
    let options = camera_options(cfg, &units, size, tiling)?;
    let mut silhouettes = Vec::new();
    if let MapKind::Silhouette { packed } = units.map {
        // Each map's silhouette pass, its events to its light probe (part
        // of the light side).
        for (((slot, light), view), probe) in slots.iter().zip(&drawn).zip(&views).zip(probes.iter_mut()) {
            let occluders = lit[slot.light].occluders();
            let texels = SilTexels::draw(packed, occluders, &light.view_projection(), view, options.shadow, probe)
                .map_err(PassError::from)?;
            silhouettes.push(texels);
        }
    }
    let mut images: Vec<CameraImage> = Vec::with_capacity(lit.len());
    let mut unmixed = Vec::with_capacity(lit.len());
    let mut next = 0;
    for (k, plan) in plans.iter().enumerate() {
        let maps = next..next + slots.iter().filter(|s| s.light == k).count();
        next = maps.end;
        let (image, own) = match plan {
            None => {
                let m = maps.start;
                bind(camera_probe, m, slots.len());
                let shade = Shade {
                    camera: &mut camera,
                    light: (drawn[m].view_projection(), triangles.as_slice()),
                    view: &views[m],
                    options: &options,
                    probe: &mut *camera_probe,
                };
                let image = match silhouettes.get(m) {
                    Some(texels) => texels.read(views[m].raster(), shade).map_err(PassError::from)??,
                    None => shade.read(&MapUnit)?,
                };
                (image, None)
            }
            Some((plan, picks)) => {
                let lights: Vec<Mat4> = drawn[maps.clone()].iter().map(Light::view_projection).collect();
                let bound: Vec<u16> = maps.clone().map(|m| u16::try_from(m).unwrap_or(u16::MAX)).collect();
                let cascades = Cascades {
                    camera: &mut camera,
                    light: (&lights, triangles.as_slice()),
                    views: &views[maps.clone()],
                    select: (&plan.select, &bound),
                    options: &options,
                    own: picks.blends(),
                    probe: &mut *camera_probe,
                };
                if silhouettes.is_empty() {
                    cascades.read_all(&vec![MapUnit; maps.len()])?
                } else {
                    let texels: Vec<&SilTexels> = silhouettes[maps.clone()].iter().collect();
                    let rasters: Vec<RasterConfig> = views[maps].iter().map(|v| *v.raster()).collect();
                    SilTexels::read_all(&texels, &rasters, cascades).map_err(PassError::from)??
                }
            }
        };
        images.push(image);
        unmixed.push(own);
    }
    let plans =
        plans.into_iter().zip(unmixed).map(|(p, own)| p.map(|(plan, picks)| (plan, picks.cascades(), own))).collect();
    Ok(Passes { light_probes: probes, images, silhouettes, triangles, drawn, plans })
}

/// A cascaded light's shading: every pixel against the cascade its depth
/// picks, through the shadow units it is given, one a cascade.
struct Cascades<'a, 'v, F: DepthFormat, C> {
    camera: &'a mut CameraFrame,
    light: (&'a [Mat4], &'a [umbra_core::shade::SceneTriangle]),
    views: &'a [MapView<'v, F>],
    select: (&'a umbra_core::shade::cascade::CascadeSelect, &'a [u16]),
    options: &'a CameraOptions,
    own: bool,
    probe: &'a mut C,
}

/// A light's image, and each pixel as its own cascade shaded it where a blend
/// band mixed two.
type LightImage = (CameraImage, Option<Vec<umbra_core::shade::Shaded>>);

impl<F: DepthFormat, C: Probe> Cascades<'_, '_, F, C> {
    fn read_all<U: ShadowUnit<F>>(self, units: &[U]) -> Result<LightImage, RenderError> {
        let Self { camera, light, views, select, options, own, probe } = self;
        Ok(shade_cascades(camera, light, (views, units), select, options, own, probe)?)
    }
}

impl<F: DepthFormat, C: Probe> SilReaderAll for Cascades<'_, '_, F, C> {
    type Out = Result<LightImage, RenderError>;

    fn read_all<S: SilStore>(self, units: &[SilhouetteUnit<'_, '_, S>]) -> Self::Out {
        Cascades::read_all(self, units)
    }
}

/// The shading of the visible pixels against one map, through the shadow
/// unit it is given.
struct Shade<'a, 'v, F: DepthFormat, C> {
    camera: &'a mut CameraFrame,
    light: (umbra_core::glam::Mat4, &'a [umbra_core::shade::SceneTriangle]),
    view: &'a MapView<'v, F>,
    options: &'a CameraOptions,
    probe: &'a mut C,
}

impl<F: DepthFormat, C: Probe> Shade<'_, '_, F, C> {
    fn read<U: ShadowUnit<F>>(self, unit: &U) -> Result<CameraImage, RenderError> {
        Ok(shade_visible(self.camera, self.light, self.view, unit, self.options, self.probe)?)
    }
}

impl<F: DepthFormat, C: Probe> SilReader for Shade<'_, '_, F, C> {
    type Out = Result<CameraImage, RenderError>;

    fn read<S: SilStore>(self, unit: &SilhouetteUnit<'_, '_, S>) -> Self::Out {
        Shade::read(self, unit)
    }
}
