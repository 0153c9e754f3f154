//! One render of a [`RenderConfig`]: the light pass for a shadow
//! algorithm, the camera pass, the exact reference and the metrics between
//! them ([`render`]); its cost on
//! architectures (`costed`); its pictures ([`pictures`]). This layer sits
//! above the passes, the cost model and the truth, and joins them.

pub mod arrays;
#[cfg(test)]
mod cache_trace;
mod cascaded;
mod config;
mod costed;
pub mod files;
#[cfg(test)]
mod ledger_property;
pub mod params;
mod passes;
pub mod pictures;
mod produced;
pub mod replay;
mod request;
pub(crate) mod shared;

use indicatif::ProgressBar;
use umbra_core::depth::Texel;
use umbra_core::shadow::{ShadowConfig, ShadowConfigError};
use umbra_core::{DepthFormat, DepthUnit, LightPassConfig, Probe, RasterConfig, TileState};

pub use self::cascaded::CascadePart;
pub(crate) use self::config::Targets;
pub use self::config::{Checked, RenderConfig, RenderConfigError};
pub use self::costed::{cost, render_costed};
pub(crate) use self::costed::{cost_others, cost_unshadowed};
pub(crate) use self::passes::{MapSlot, map_slots};
use self::passes::{Passes, passes};
pub use self::produced::{LightPart, PartRef, Render};
use self::replay::{PassInputs, ShadowSource, judged};
pub use self::request::RenderRequest;
use crate::base::counters::Counters;
use crate::base::maps::{Tiling, with_format};
use crate::base::probes::Tee;
use crate::input::limits::LimitError;
use crate::pass::PassError;
pub(crate) use crate::pass::algorithm::{Algorithm, Culling};
use crate::pass::camera::{CameraFrame, CameraOptions, map_view, visibility};
use crate::pass::light::{self, LightFrame, LightMaps, RawMaps};
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
    let none = (vec![umbra_core::NoProbe; map_slots(scene, cfg, checked.map)?.len()], &mut umbra_core::NoProbe);
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
    let slots = map_slots(scene, cfg, checked.map)?;
    let light_probes =
        light_also.into_iter().zip(&slots).map(|(also, slot)| Tee(Counters::new(&slot.raster), also)).collect();
    let Passes { light_probes: probes, images, silhouettes, triangles, drawn, plans } = passes::<F, _, _>(
        (scene, lit),
        cfg,
        (checked, &slots),
        &mut frames,
        light_probes,
        &mut Tee(&mut camera_events, camera_also),
        Tiling::DEFAULT,
    )?;
    let (light_events, light_also): (Vec<Counters>, Vec<L>) = probes.into_iter().map(|Tee(a, b)| (a, b)).unzip();
    let several = images.len() > 1;
    for (((slot, frame), events), light) in slots.iter().zip(&frames).zip(&light_events).zip(&drawn) {
        if frame.maps().is_some() {
            let key = slot.key(plans.get(slot.light).is_some_and(Option::is_some));
            crate::pass::light::EmptyMap::check(&events.totals, &key, Some(light.planes()))?;
        }
    }
    let reference = Reference::of(scene)?;
    let Some(seen) = images.first() else { return Err(RenderError::nothing_evaluated(scene)) };
    let ids: Vec<u32> = seen.pixels.iter().map(|p| p.triangle).collect();
    let truths = truths_of(cfg, truth_from, (&ids, seen.camera), (&reference, &light_sources(scene)), scene)?;
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let options = camera_options(cfg, &units, (seen.width, seen.height), Tiling::DEFAULT)?;
    let of_light = |e: RenderError, k: usize| if several { e.of_light(k) } else { e };
    let raw = |maps: Option<&LightMaps<F::Texel>>| {
        maps.map_or_else(
            // Shadow volumes draw no map: one far texel stands for it.
            || LightMaps {
                config: LightPassConfig { raster: checked.map, unit: DepthUnit::Single, max_z_cull: true },
                z1: vec![F::Texel::to_raw(F::FAR)],
                z2: Vec::new(),
                tiles: vec![TileState::cleared(F::Texel::to_raw(F::FAR), 1)],
            },
            light::widen,
        )
    };
    let mut events = light_events.into_iter();
    let mut parts = Vec::with_capacity(images.len());
    for (k, ((image, truth), plan)) in images.into_iter().zip(truths).zip(plans).enumerate() {
        let fields = Fields::new(&truth, image.width);
        let maps: Vec<usize> = (0..slots.len()).filter(|&m| slots[m].light == k).collect();
        let views = maps
            .iter()
            .map(|&m| {
                frames.get(m).and_then(LightFrame::maps).map(|f| map_view::<F>(f, units.front_culled)).transpose()
            })
            .collect::<Result<Vec<_>, _>>()?;
        let inputs: Vec<PassInputs<'_, F>> = maps
            .iter()
            .zip(&views)
            .map(|(&m, view)| PassInputs {
                light: drawn[m],
                triangles: &triangles,
                seen: (&ids, image.camera),
                view: view.as_ref(),
                options: &options,
                source: ShadowSource::of(units.map, silhouettes.get(m)),
                memo: None,
            })
            .collect();
        let (metrics, verdicts, cascades, cascade_of) = match &plan {
            Some((_, cascade_of, own)) => {
                let pixels = (&image.pixels[..], own.as_deref().unwrap_or(&image.pixels), &cascade_of[..]);
                let (m, v, each) = cascaded::judged(&inputs, pixels, (&truth, &fields, &reference))
                    .map_err(|e| of_light(RenderError::Pass(e), k))?;
                (m, v, each, cascade_of.clone())
            }
            None => {
                let (m, v) = judged(&inputs[0], &image.pixels, (&truth, &fields, &reference), None)
                    .map_err(|e| of_light(RenderError::Pass(e), k))?;
                (m, v, Vec::new(), Vec::new())
            }
        };
        let mut raws =
            maps.iter().map(|&m| RawMaps { format: cfg.format, maps: raw(frames.get(m).and_then(LightFrame::maps)) });
        // Every light draws a map: a slot a light, at least.
        let Some(first) = raws.next() else { return Err(RenderError::nothing_evaluated(scene)) };
        let counted: Vec<Counters> = events.by_ref().take(maps.len()).collect();
        let cascades = match plan {
            Some((plan, ..)) => cascades
                .into_iter()
                .zip(&counted)
                .enumerate()
                .map(|(c, (metrics, events))| CascadePart {
                    light: plan.lights[c],
                    slice: [plan.distances[c], plan.distances[c + 1]],
                    side: plan.sides[c],
                    metrics,
                    events: events.totals,
                })
                .collect(),
            None => Vec::new(),
        };
        let light_events = counted.into_iter().next().unwrap_or_default();
        parts.push(LightPart {
            image,
            maps: first,
            truth,
            metrics,
            verdicts,
            light_events,
            cascades,
            cascade_maps: raws.collect(),
            cascade_of,
        });
    }
    let first = parts.remove(0);
    let LightPart { image, maps, truth, metrics, verdicts, light_events, cascades, cascade_maps, cascade_of } = first;
    let size = (image.width, image.height);
    let shadowless =
        scene.shadowless.iter().map(|l| reference.facing(&ids, &image.camera, size, &l.source())).collect();
    let render = Render {
        image,
        maps,
        truth,
        metrics,
        verdicts,
        light_events,
        camera_events,
        command,
        more: parts,
        shadowless,
        cascades,
        cascade_maps,
        cascade_of,
    };
    Ok((render, light_also))
}
