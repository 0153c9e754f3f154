//! One configuration rendered from its shares: a shading for each distinct
//! pair of visibility and map, fanned out to the architectures that drew
//! it, then the metrics and every architecture's report.

use core::ops::Range;

use glam::Mat4;
use umbra_core::probe::{Probe, Totals};
use umbra_core::shade::{MapUnit, PixelResult, SceneTriangle, ShadeSetup, Shaded, ShadowUnit, SilhouetteUnit};
use umbra_core::shadow::{MapView, Shadow, TileBounds};
use umbra_core::silhouette::SilStore;
use umbra_core::{DepthFormat, RasterConfig};

use super::probes::{Kept, Probes, Reporting, copy_of};
use super::seen::Lighting;
use super::{ImageShare, LightShare, shares};
use crate::base::maps::Tiling;
use crate::base::probes::Tee;
use crate::cost::report::CostReport;
use crate::pass::PassError;
use crate::pass::algorithm::{MapKind, Units};
use crate::pass::camera::{Bands, CameraOptions, map_view, shade};
use crate::pass::occluders::{SilReader, SilTexels};
use crate::render::camera_options;
use crate::render::replay::{PassInputs, ShadowSource, with_judge};
use crate::render::{RenderConfig, RenderError};
use crate::truth::metrics::{Metrics, Sums};
use crate::world::occluders::Lit;
use crate::world::scene::Scene;

/// Buffers a configuration's shading reuses from the last one a thread
/// rendered: the results (whole for the metrics; for the other shadings
/// only the shadow, which reports the same events) and the shading unit's
/// setup store.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    pixels: Vec<Shaded>,
    others: Vec<Shadow>,
    setups: Vec<ShadeSetup>,
}

/// What one configuration's shared render gives: its frame's metrics
/// (over its lights' parts, as [`crate::render::Render::frame_metrics`]),
/// the event totals of its camera pass, and for each architecture that
/// [`shares`] its cost (`None` for the others, costed on their own).
pub(crate) type SharedRender = (Metrics, Totals, Vec<Option<Result<CostReport, RenderError>>>);

/// Render `cfg` from what it shares, in format `F`, with `scratch`'s
/// buffers: `lights` holds each shadow-casting light's share of `cfg`'s
/// key, in the scene's order. As a render on its own does, each light is
/// shaded in turn against its map after the one visibility, every camera
/// probe told which map it reads. `None` when anything fails, for the
/// configuration to render on its own and report why.
#[must_use]
pub(crate) fn render_shared<F: DepthFormat>(
    image: &ImageShare<'_>,
    lights: &[LightShare<F::Texel>],
    cfg: &RenderConfig,
    scratch: &mut Scratch,
) -> Option<SharedRender> {
    let job = cfg.check(image.scene, &image.limits).ok()?;
    let checked = job.targets(RasterConfig::DEFAULT_TILE_SIZE).ok()?;
    for a in image.archs.iter().filter(|a| shares(a)) {
        job.targets(a.tiling().tile).ok()?;
    }
    if (checked.image.width(), checked.image.height()) != image.size || lights.len() != image.lights.len() {
        return None;
    }
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let options = camera_options(cfg, &units, image.size, Tiling::DEFAULT).ok()?;
    // Each sharing architecture's camera probe, continued light by light,
    // and its light probes, one a light.
    let mut cameras: Vec<Option<Kept>> = (0..image.archs.len())
        .map(|i| Some(copy_of(&image.seen[image.seen_by[i]?].probes, i)?.reading(cfg, &units)))
        .collect();
    let mut light_probes: Vec<Vec<Kept>> = (0..image.archs.len()).map(|_| Vec::with_capacity(lights.len())).collect();
    let mut camera_totals = image.seen[0].totals;
    let mut parts = Vec::with_capacity(lights.len());
    for (l, ((lighting, lit), light)) in image.lights.iter().zip(&image.lit).zip(lights).enumerate() {
        let one = Light { lighting, lit, light, index: l, of: lights.len() };
        let each = One { image, light: one, options: &options, units: &units };
        parts.push(each.shade::<F>(scratch, (&mut cameras, &mut light_probes), &mut camera_totals)?);
    }
    let config = cfg.describe();
    let names = (image.scene.name.as_str(), &image.counts);
    let costs = cameras
        .into_iter()
        .zip(light_probes)
        .map(|(camera, lights)| Some(Ok(Kept::report(names, cfg, &config, lights, camera?)?)))
        .collect();
    let metrics = if parts.len() == 1 { parts[0] } else { Metrics::of_lights(&parts) };
    Some((metrics, camera_totals, costs))
}

/// One light of a shared render: what its shadings read, the scene as it
/// lights it, and its share of the configuration's key, its index among
/// the scene's `of` lights.
#[derive(Clone, Copy)]
struct Light<'i, 's, T> {
    lighting: &'i Lighting<'s>,
    lit: &'i Lit<'s>,
    light: &'i LightShare<T>,
    index: usize,
    of: usize,
}

/// A configuration's shadings against one light.
struct One<'i, 's, T> {
    image: &'i ImageShare<'s>,
    light: Light<'i, 's, T>,
    options: &'i CameraOptions,
    units: &'i Units,
}

impl<T: umbra_core::depth::Texel> One<'_, '_, T> {
    /// Each shading of a distinct pair of visibility and map against this
    /// light, its events to the camera probes of the architectures that
    /// drew it (`cameras`, told first that the shadow unit reads this
    /// light's map) and to `camera_totals` for the functional one; the
    /// light probes it continued (for a silhouette map) added to each
    /// architecture's list. The functional render's metrics for this light.
    fn shade<F: DepthFormat<Texel = T>>(
        &self,
        scratch: &mut Scratch,
        (cameras, light_probes): (&mut [Option<Kept>], &mut [Vec<Kept>]),
        camera_totals: &mut Totals,
    ) -> Option<Metrics> {
        let Self { image, light: Light { lighting, lit, light, index, of }, options, units } = *self;
        let Scratch { pixels, others, setups } = scratch;
        let mut metrics = None;
        for (k, Class { seen, bounds, members }) in classes(image, light)?.into_iter().enumerate() {
            let (mut lights, mut probes) = (Probes::default(), Probes::default());
            for &(i, tiling) in &members {
                lights.push(i, copy_of(&light.probes, i)?);
                probes.push(i, cameras.get_mut(i)?.take()?.in_tiling(tiling));
            }
            if of > 1 {
                probes.run(Bound(u16::try_from(index).unwrap_or(u16::MAX)));
            }
            let tilings = bounds[1..]
                .iter()
                .map(|&b| TileBounds::new(light.lit[b].maps.config.raster, &light.lit[b].maps.tiles))
                .collect::<Result<Vec<_>, _>>()
                .ok()?;
            let view =
                map_view::<F>(&light.lit[bounds[0]].maps, units.front_culled).ok()?.with_tilings(&tilings).ok()?;
            let seen = &image.seen[seen];
            let seen = (seen.frame.ids(), seen.camera);
            let scene: &Scene = &lit.scene;
            // The silhouette pass over this shading's map, once: its events
            // to the light probes, its texels to the shading and the judge.
            let silhouette = match units.map {
                MapKind::Silhouette { packed } => {
                    Some(lights.run(Silhouettes { lit, view: &view, options, packed }).ok()?)
                }
                MapKind::Depth | MapKind::Volumes => None,
            };
            let silhouette = silhouette.as_ref();
            if k == 0 {
                // The functional render, its metrics summed band by band as
                // it is shaded, each wrong pixel judged by replaying it; the
                // map's footprint one kept when the pixels' points are its
                // own.
                let source = ShadowSource::of(units.map, silhouette);
                let triangles = &image.triangles;
                let memo = Some(&lighting.occluders);
                let inputs =
                    PassInputs { light: scene.light(), triangles, seen, view: Some(&view), options, source, memo };
                let mut sums = Sums::new(pixels.len());
                let kept = lighting.kept_footprints();
                let mut fit = vec![true; kept.len()];
                let done = with_judge(&inputs, (&image.reference, &lighting.fields), |judge| {
                    let mut then = |band: Range<usize>, out: &[Shaded]| {
                        sums.add(band.clone(), out, lighting.truth, &lighting.fields, judge);
                        for (f, fits) in kept.iter().zip(&mut fit) {
                            *fits = *fits && f.fits_in(band.clone(), out);
                        }
                    };
                    let bands = Some(Bands { rows: BAND_ROWS, then: &mut then });
                    let pass = Shading {
                        light: (scene.light().view_projection(), &image.triangles),
                        view: &view,
                        options,
                        seen,
                        out: &mut *pixels,
                        setups,
                        bands,
                    };
                    pass.run(image.size, silhouette, &mut probes, camera_totals)
                });
                done.ok()?.ok()?;
                let fits = kept.iter().zip(fit).find_map(|(f, fits)| fits.then_some(f));
                let footprints = lighting.footprints(pixels, image.size.0, fits);
                metrics = Some(sums.finish(pixels, lighting.truth, &lighting.fields, Some(&footprints)).0);
            } else {
                let pass = Shading {
                    light: (scene.light().view_projection(), &image.triangles),
                    view: &view,
                    options,
                    seen,
                    out: &mut *others,
                    setups,
                    bands: None,
                };
                pass.run(image.size, silhouette, &mut probes, &mut umbra_core::NoProbe).ok()?;
            }
            for (i, p) in lights.into_kept() {
                light_probes.get_mut(i)?.push(p);
            }
            for (i, p) in probes.into_kept() {
                *cameras.get_mut(i)? = Some(p);
            }
        }
        metrics
    }
}

/// Tell every probe that the shadow unit now reads light `.0`'s map, as
/// [`Reporting`].
struct Bound(u16);

impl Reporting for Bound {
    type Out = ();

    fn run<P: Probe>(self, probe: &mut P) {
        probe.map_bound(self.0);
    }
}

/// One shading of a configuration: the visibility it shades (its first
/// pass), the light passes whose tiles' bounds its lookups are tested
/// against (their first passes, the map's own first: each holds the same
/// texels), and the architectures that drew it, each with the index of its
/// tiling among them.
struct Class {
    seen: usize,
    bounds: Vec<usize>,
    members: Vec<(usize, usize)>,
}

/// The shadings of a configuration, the functional render's first (the
/// default tiling's visibility and map, its bounds the map's own).
fn classes<T>(image: &ImageShare<'_>, light: &LightShare<T>) -> Option<Vec<Class>> {
    let first = &light.lit[0];
    let mut classes = vec![Class { seen: image.seen[0].class, bounds: vec![first.class], members: vec![] }];
    let mut texels = vec![first.texels];
    for i in 0..image.archs.len() {
        let (Some(seen), Some(lit)) = (image.seen_by[i], light.lit_by[i]) else { continue };
        let (seen, lit) = (image.seen[seen].class, &light.lit[lit]);
        let k = match classes.iter().zip(&texels).position(|(c, &t)| c.seen == seen && t == lit.texels) {
            Some(k) => k,
            None => {
                classes.push(Class { seen, bounds: vec![], members: vec![] });
                texels.push(lit.texels);
                classes.len() - 1
            }
        };
        let class = classes.get_mut(k)?;
        let tiling = class.bounds.iter().position(|&b| b == lit.class).unwrap_or_else(|| {
            class.bounds.push(lit.class);
            class.bounds.len() - 1
        });
        class.members.push((i, tiling));
    }
    Some(classes)
}

/// Rows of a band of the functional render that its metrics sum while it
/// is fresh: 16 rows of a 1920-pixel image are 1.2 MB of results.
const BAND_ROWS: u32 = 16;

/// One shading of a configuration: the map it reads, the visibility it
/// shades, the buffers it writes and what reads them as they are written.
struct Shading<'p, 'v, F: DepthFormat, R> {
    /// The map's light's view-projection, and the scene's triangles.
    light: (glam::Mat4, &'p [SceneTriangle]),
    view: &'p MapView<'v, F>,
    options: &'p CameraOptions,
    seen: (&'p [u32], Mat4),
    out: &'p mut Vec<R>,
    setups: &'p mut Vec<ShadeSetup>,
    bands: Option<Bands<'p, R>>,
}

impl<F: DepthFormat, R: PixelResult> Shading<'_, '_, F, R> {
    /// The shading of an image of `size` through the silhouette unit over
    /// `silhouette`, when the algorithm drew one, or the map's own unit:
    /// its events to the camera probes and to `also`.
    fn run<P: Probe>(
        self,
        size: (u32, u32),
        silhouette: Option<&SilTexels>,
        cameras: &mut Probes,
        also: &mut P,
    ) -> Result<(), RenderError> {
        match silhouette {
            Some(texels) => {
                let raster = *self.view.raster();
                texels.read(&raster, Tallied { shading: self, size, cameras, also }).map_err(PassError::from)?
            }
            None => self.tallied(&MapUnit, size, cameras, also),
        }
    }

    /// The shading with shadow unit `unit`, its events to `also` and
    /// tallied once for every camera probe, each probe then costed from the
    /// tally.
    fn tallied<U: ShadowUnit<F>, P: Probe>(
        self,
        unit: &U,
        size: (u32, u32),
        cameras: &mut Probes,
        also: &mut P,
    ) -> Result<(), RenderError> {
        let mut tally = cameras.tally(size);
        Unit { shading: self, unit, also }.run(&mut tally)?;
        if tally.unexpected {
            return Err(RenderError::Cost("the shading reported an event its tally does not count".into()));
        }
        cameras.absorb(&tally.closed());
        Ok(())
    }
}

/// The silhouette pass over a shading's map, as [`Reporting`].
struct Silhouettes<'p, 'v, F: DepthFormat> {
    lit: &'p Lit<'p>,
    view: &'p MapView<'v, F>,
    options: &'p CameraOptions,
    packed: bool,
}

impl<F: DepthFormat> Reporting for Silhouettes<'_, '_, F> {
    type Out = Result<SilTexels, RenderError>;

    fn run<P: Probe>(self, probe: &mut P) -> Self::Out {
        let light = self.lit.scene.light().view_projection();
        let shadow = self.options.shadow;
        Ok(SilTexels::draw(self.packed, self.lit.occluders(), &light, self.view, shadow, probe)
            .map_err(PassError::from)?)
    }
}

/// A shading through a silhouette unit, tallied, as [`SilReader`].
struct Tallied<'s, 'p, 'v, F: DepthFormat, R, P> {
    shading: Shading<'p, 'v, F, R>,
    size: (u32, u32),
    cameras: &'s mut Probes,
    also: &'s mut P,
}

impl<F: DepthFormat, R: PixelResult, P: Probe> SilReader for Tallied<'_, '_, '_, F, R, P> {
    type Out = Result<(), RenderError>;

    fn read<S: SilStore>(self, unit: &SilhouetteUnit<'_, '_, S>) -> Self::Out {
        self.shading.tallied(unit, self.size, self.cameras, self.also)
    }
}

/// The shading with a shadow unit, its events to the probes and to `also`,
/// as [`Reporting`].
struct Unit<'s, 'p, 'v, F: DepthFormat, R, U, A> {
    shading: Shading<'p, 'v, F, R>,
    unit: &'s U,
    also: &'s mut A,
}

impl<F: DepthFormat, R: PixelResult, U: ShadowUnit<F>, A: Probe> Reporting for Unit<'_, '_, '_, F, R, U, A> {
    type Out = Result<(), RenderError>;

    fn run<P: Probe>(self, probe: &mut P) -> Self::Out {
        let Shading { light, view, options, seen, out, setups, bands } = self.shading;
        shade(light, seen, view, self.unit, options, &mut Tee(self.also, probe), out, setups, bands)?;
        Ok(())
    }
}
