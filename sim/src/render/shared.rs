//! Renders that share what does not change between them: a study's
//! configurations of one scene and image size.
//!
//! What each part of a render reads decides who shares it:
//!
//! * the camera's **visibility** reads the scene, the image and the
//!   architecture's tiling — never the algorithm or the map — so it is drawn
//!   once per tiling ([`Seen`]), and each architecture's camera probe is
//!   kept as the visibility left it, for every configuration to continue;
//! * the **light pass** reads the scene, the depth unit and the culling,
//!   the depth format, the map side and the tiling — never the filter, the
//!   shadow test or its bias — so it is drawn once per tiling for every
//!   configuration with the same [`LightKey`] ([`LightShare`]), each
//!   architecture's light probe kept as it left it;
//! * the **shading** reads the visible ids, the map's texels and its tiles'
//!   bounds (lookup culling): it runs once per configuration for each
//!   distinct pair of them, feeding every architecture that drew that pair
//!   at once (pixel coordinates, not the tiling, place its events);
//! * the **reference's** boundaries and distance fields ([`Fields`]) are
//!   worked out once per scene and image.
//!
//! A probe continued from a kept copy receives exactly the events, in
//! exactly the order, that a probe of its own passes would: every report is
//! the unshared render's bit for bit (`study::run_unshared` is the
//! reference the tests hold it to). An architecture that shades per
//! fragment charges its filter during visibility, so it keeps passes of its
//! own ([`shares`]).

use glam::Mat4;
use rayon::prelude::*;
use umbra_core::probe::Totals;
use umbra_core::shade::{MapUnit, ShadeSetup, Shaded, ShadowUnit, SilhouetteUnit};
use umbra_core::shadow::{MapView, ShadowConfig};
use umbra_core::silhouette::{Packed, SilPoint, SilStore, SilhouetteMap};
use umbra_core::{CullMode, DepthFormat, DepthUnit, LightPassConfig, Probe, RasterConfig, TileState};

use super::costed::{SceneCounts, Shape, reading, report, shape};
use super::{RenderConfig, RenderError};
use crate::base::maps::Tiling;
use crate::base::probes::{Fan, Tee};
use crate::cost::arch::{Arch, ArchProbe, CostReport, PassKind};
use crate::io::limits::Limits;
use crate::pass::PassError;
use crate::pass::algorithm::MapKind;
use crate::pass::camera::{CameraFrame, CameraOptions, map_view, shade, visibility};
use crate::pass::light::{LightMaps, LightOptions};
use crate::pass::occluders::silhouette_map;
use crate::truth::metrics::{Fields, Metrics, compare_with};
use crate::truth::reference::PixelTruth;
use crate::world::occluders::Occluders;
use crate::world::scene::Scene;

/// Whether `arch`'s passes can be shared: one that shades per fragment
/// charges the filter's instructions on the visibility pass's depth writes,
/// so its visibility is not the same for every configuration.
#[must_use]
pub fn shares(arch: &Arch) -> bool {
    !arch.shade.per_fragment
}

/// A probe kept as a pass left it, of either kind of architecture: one
/// that needs each fragment's address (a depth cache in front of off-chip
/// depth) or one that does not.
#[derive(Clone, Debug)]
enum Kept {
    Plain(ArchProbe<false>),
    Detail(ArchProbe<true>),
}

/// Probes of several architectures, split by kind so each kind is one
/// [`Fan`]: `(architecture index, probe)`.
#[derive(Debug, Default)]
struct Probes {
    plain: Vec<(usize, ArchProbe<false>)>,
    detail: Vec<(usize, ArchProbe<true>)>,
}

impl Probes {
    fn push(&mut self, arch: usize, p: Kept) {
        match p {
            Kept::Plain(p) => self.plain.push((arch, p)),
            Kept::Detail(p) => self.detail.push((arch, p)),
        }
    }

    /// Run `pass` with every probe fanned out (the probes keep their order
    /// within each kind), then put them back.
    fn run<T>(&mut self, pass: impl FnOnce(&mut Tee<Fan<ArchProbe<false>>, Fan<ArchProbe<true>>>) -> T) -> T {
        let (ai, plain): (Vec<usize>, Vec<_>) = std::mem::take(&mut self.plain).into_iter().unzip();
        let (bi, detail): (Vec<usize>, Vec<_>) = std::mem::take(&mut self.detail).into_iter().unzip();
        let mut fan = Tee(Fan(plain), Fan(detail));
        let out = pass(&mut fan);
        let Tee(Fan(plain), Fan(detail)) = fan;
        self.plain = ai.into_iter().zip(plain).collect();
        self.detail = bi.into_iter().zip(detail).collect();
        out
    }

    /// The probes, by architecture.
    fn into_kept(self) -> Vec<(usize, Kept)> {
        let mut all: Vec<(usize, Kept)> = self.plain.into_iter().map(|(i, p)| (i, Kept::Plain(p))).collect();
        all.extend(self.detail.into_iter().map(|(i, p)| (i, Kept::Detail(p))));
        all.sort_by_key(|(i, _)| *i);
        all
    }
}

/// One visibility pass, in one tiling, and what it left.
#[derive(Debug)]
struct Seen {
    /// The first pass (this one or an earlier) with the same visible ids:
    /// passes with the same ids shade alike.
    class: usize,
    frame: CameraFrame,
    camera: Mat4,
    /// The pass's events, totalled.
    totals: Totals,
    /// The camera probes of the architectures drawn in this tiling, as the
    /// pass left them (they read no map yet).
    probes: Vec<(usize, Kept)>,
}

/// A visibility pass's frame, camera, event totals and probes.
type Drawn = (CameraFrame, Mat4, Totals, Vec<(usize, Kept)>);

/// What the renders of one scene at one image size share: the reference
/// with its [`Fields`], a visibility pass per tiling, the scene's counts.
#[derive(Debug)]
pub struct ImageShare<'s> {
    scene: &'s Scene,
    size: (u32, u32),
    truth: &'s [Option<PixelTruth>],
    fields: Fields,
    archs: &'s [Arch],
    limits: Limits,
    /// The default tiling's first, then each architecture's.
    seen: Vec<Seen>,
    /// For each architecture that [`shares`], its entry in `seen`.
    seen_by: Vec<Option<usize>>,
    counts: SceneCounts,
    occluders: Occluders,
}

impl<'s> ImageShare<'s> {
    /// The visibility of `scene` at `size` in the default tiling and in
    /// each tiling of `archs`, and the reference `truth`'s fields: `None`
    /// when the reference has no pixel to measure or a pass cannot run, for
    /// each configuration to render (and fail) on its own.
    #[must_use]
    pub fn new(
        scene: &'s Scene,
        size: (u32, u32),
        truth: &'s [Option<PixelTruth>],
        archs: &'s [Arch],
        limits: &Limits,
    ) -> Option<Self> {
        let pixels = u64::from(size.0) * u64::from(size.1);
        if truth.len() as u64 != pixels || !truth.iter().flatten().any(|t| t.faces_light) {
            return None;
        }
        let mut tilings = vec![Tiling::DEFAULT];
        let mut seen_by = Vec::with_capacity(archs.len());
        for a in archs {
            seen_by.push(shares(a).then(|| {
                let t = a.tiling();
                tilings.iter().position(|&s| s == t).unwrap_or_else(|| {
                    tilings.push(t);
                    tilings.len() - 1
                })
            }));
        }
        // Each tiling's pass, in parallel.
        let drawn: Vec<Option<Drawn>> = tilings
            .par_iter()
            .enumerate()
            .map(|(k, &tiling)| {
                let raster =
                    RasterConfig::new(size.0, size.1, tiling.tile, RasterConfig::DEFAULT_SUBPIXEL_BITS).ok()?;
                let mut probes = Probes::default();
                for (i, a) in archs.iter().enumerate().filter(|&(i, _)| seen_by[i] == Some(k)) {
                    let format = umbra_core::DepthFormatKind::D24;
                    probes.push(
                        i,
                        if shape(a).camera_addresses {
                            Kept::Detail(ArchProbe::new(a, PassKind::Camera, raster, format, 1))
                        } else {
                            Kept::Plain(ArchProbe::new(a, PassKind::Camera, raster, format, 1))
                        },
                    );
                }
                let mut frame = CameraFrame::default();
                let mut totals = Totals::default();
                let vis =
                    probes.run(|fan| visibility(&mut frame, scene, size, tiling, &mut Tee(&mut totals, fan))).ok()?;
                Some((frame, vis.camera, totals, probes.into_kept()))
            })
            .collect();
        let mut seen: Vec<Seen> = Vec::with_capacity(tilings.len());
        for (k, pass) in drawn.into_iter().enumerate() {
            let (frame, camera, totals, probes) = pass?;
            let class = seen.iter().position(|s| s.frame.ids() == frame.ids()).unwrap_or(k);
            seen.push(Seen { class, frame, camera, totals, probes });
        }
        Some(Self {
            scene,
            size,
            truth,
            fields: Fields::new(truth, size.0),
            archs,
            limits: *limits,
            seen,
            seen_by,
            counts: SceneCounts::of(scene),
            occluders: Occluders::new(scene),
        })
    }
}

/// What a light pass reads of a configuration: configurations with the
/// same key draw the same maps with the same events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightKey {
    format: umbra_core::DepthFormatKind,
    map_size: u32,
    unit: DepthUnit,
    solids: CullMode,
    open: CullMode,
}

impl LightKey {
    /// The key of `cfg`: `None` for shadow volumes, which draw no map.
    #[must_use]
    pub fn of(cfg: &RenderConfig) -> Option<Self> {
        // The unit and its culling do not depend on the format.
        let units = cfg.algorithm.units::<umbra_core::D24>(cfg.bias);
        (units.map != MapKind::Volumes).then(|| Self {
            format: cfg.format,
            map_size: cfg.map_size,
            unit: units.unit,
            solids: units.cull(true, cfg.culling),
            open: units.cull(false, cfg.culling),
        })
    }
}

/// One light pass, in one tiling, and what it left.
#[derive(Debug)]
struct Lit<T> {
    /// The first pass (this one or an earlier) whose maps shade alike:
    /// the same texels and the same tile bounds.
    class: usize,
    maps: LightMaps<T>,
}

/// What the configurations with one [`LightKey`] share: a light pass per
/// tiling of the architectures (and the default one), each architecture's
/// light probe as its pass left it.
#[derive(Debug)]
pub struct LightShare<T> {
    /// The default tiling's first.
    lit: Vec<Lit<T>>,
    /// For each architecture that [`shares`], its entry in `lit`.
    lit_by: Vec<Option<usize>>,
    probes: Vec<(usize, Kept)>,
    /// Triangles the default pass set up (none: the light sees nothing).
    setups: u64,
}

/// Whether two maps shade alike: the shadow unit reads their texels and
/// their tiles' bounds (to cull lookups), nothing else.
fn alike<T: PartialEq + Copy>(a: &LightMaps<T>, b: &LightMaps<T>) -> bool {
    let bounds = |t: &TileState<T>| [t.z1_min, t.z1_max, t.z2_min, t.z2_max];
    a.config.raster == b.config.raster
        && a.z1 == b.z1
        && a.z2 == b.z2
        && a.tiles.len() == b.tiles.len()
        && a.tiles.iter().zip(&b.tiles).all(|(x, y)| bounds(x) == bounds(y))
}

impl<T: umbra_core::depth::Texel> LightShare<T> {
    /// The light passes of `cfg` (any configuration of its key) in format
    /// `F`: `None` when one cannot run, for each configuration to render
    /// (and fail) on its own.
    #[must_use]
    pub fn new<F: DepthFormat<Texel = T>>(image: &ImageShare<'_>, cfg: &RenderConfig) -> Option<Self> {
        let scene = image.scene;
        let units = cfg.algorithm.units::<F>(cfg.bias);
        let mut shapes = vec![(Tiling::DEFAULT, false)];
        let mut lit_by = Vec::with_capacity(image.archs.len());
        for a in image.archs {
            lit_by.push(shares(a).then(|| {
                let s = shape(a);
                let key = (s.tiling, s.light_addresses);
                shapes.iter().position(|&k| k == key).unwrap_or_else(|| {
                    shapes.push(key);
                    shapes.len() - 1
                })
            }));
        }
        let draws = scene.draws_culled(scene.light().view_projection(), |solid| units.cull(solid, cfg.culling));
        let (mut lit, mut kept, mut setups) = (Vec::<Lit<T>>::new(), Vec::new(), 0);
        for (k, &(tiling, addresses)) in shapes.iter().enumerate() {
            let checked = cfg.check(scene, &image.limits, tiling.tile).ok()?;
            let config = LightPassConfig { raster: checked.map, unit: units.unit, max_z_cull: true };
            let options = LightOptions { per_draw: tiling.per_draw, ..LightOptions::default() };
            let mine = image.archs.iter().enumerate().filter(|&(i, _)| lit_by[i] == Some(k));
            let buffers = units.unit.buffers();
            let mut totals = Totals::default();
            let maps = if addresses {
                let (ids, probes): (Vec<usize>, Vec<ArchProbe<true>>) =
                    mine.map(|(i, a)| (i, light_probe(a, checked.map, cfg, buffers))).unzip();
                let (maps, Tee(_, Fan(probes))) =
                    LightMaps::draw::<F, _>(config, &draws, options, Tee(&mut totals, Fan(probes))).ok()?;
                kept.extend(ids.into_iter().zip(probes.into_iter().map(Kept::Detail)));
                maps
            } else {
                let (ids, probes): (Vec<usize>, Vec<ArchProbe<false>>) =
                    mine.map(|(i, a)| (i, light_probe(a, checked.map, cfg, buffers))).unzip();
                let (maps, Tee(_, Fan(probes))) =
                    LightMaps::draw::<F, _>(config, &draws, options, Tee(&mut totals, Fan(probes))).ok()?;
                kept.extend(ids.into_iter().zip(probes.into_iter().map(Kept::Plain)));
                maps
            };
            if k == 0 {
                setups = totals.setups;
            }
            let class = lit.iter().position(|l| alike(&l.maps, &maps)).unwrap_or(k);
            lit.push(Lit { class, maps });
        }
        kept.sort_by_key(|(i, _)| *i);
        Some(Self { lit, lit_by, probes: kept, setups })
    }
}

/// The light pass's probe of `arch` over `raster`, for `cfg`'s format and a
/// unit of `buffers` depth buffers.
fn light_probe<const D: bool>(arch: &Arch, raster: RasterConfig, cfg: &RenderConfig, buffers: u32) -> ArchProbe<D> {
    ArchProbe::new(arch, PassKind::Light, raster, cfg.format, buffers)
}

/// Buffers a configuration's shading reuses from the last one a thread
/// rendered: the results and the shading unit's setup store.
#[derive(Debug, Default)]
pub struct Scratch {
    pixels: Vec<Shaded>,
    others: Vec<Shaded>,
    setups: Vec<ShadeSetup>,
}

/// What one configuration's shared render gives: its metrics, the share of
/// its shaded pixels that needed a tangent plane, and for each architecture
/// that [`shares`] its cost (`None` for the others, costed on their own).
pub type SharedRender = (Metrics, f64, Vec<Option<Result<CostReport, RenderError>>>);

/// Render `cfg` (of `light`'s key) from what it shares, in format `F`,
/// with `scratch`'s buffers: `None` when anything fails, for the
/// configuration to render on its own and report why.
#[must_use]
pub fn render_shared<F: DepthFormat>(
    image: &ImageShare<'_>,
    light: &LightShare<F::Texel>,
    cfg: &RenderConfig,
    scratch: &mut Scratch,
) -> Option<SharedRender> {
    let scene = image.scene;
    let checked = cfg.check(scene, &image.limits, RasterConfig::DEFAULT_TILE_SIZE).ok()?;
    for a in image.archs.iter().filter(|a| shares(a)) {
        cfg.check(scene, &image.limits, a.tiling().tile).ok()?;
    }
    if (checked.image.width(), checked.image.height()) != image.size || light.setups == 0 {
        return None;
    }
    let units = cfg.algorithm.units::<F>(cfg.bias);
    let options = CameraOptions {
        width: image.size.0,
        height: image.size.1,
        shadow: ShadowConfig::new(units.test, units.bias, cfg.filter, true).ok()?,
        virtual_samples: units.virtual_samples(cfg.virtual_samples),
        tiling: Tiling::DEFAULT,
    };
    // The shading classes, the functional render's first: each a pair of
    // visibility and map classes, and the architectures that drew it.
    let class_of = |i: usize| Some((image.seen[image.seen_by[i]?].class, light.lit[light.lit_by[i]?].class));
    let mut classes: Vec<((usize, usize), Vec<usize>)> = vec![((image.seen[0].class, light.lit[0].class), vec![])];
    for i in 0..image.archs.len() {
        let Some(key) = class_of(i) else { continue };
        match classes.iter_mut().find(|c| c.0 == key) {
            Some(c) => c.1.push(i),
            None => classes.push((key, vec![i])),
        }
    }
    let mut costs: Vec<Option<Result<CostReport, RenderError>>> = (0..image.archs.len()).map(|_| None).collect();
    let mut camera_totals = image.seen[0].totals;
    let config = cfg.describe();
    let Scratch { pixels, others, setups } = scratch;
    for (k, ((seen, lit), members)) in classes.into_iter().enumerate() {
        let (mut lights, mut cameras) = (Probes::default(), Probes::default());
        for &i in &members {
            let kept = |list: &[(usize, Kept)]| list.iter().find(|(j, _)| *j == i).map(|(_, p)| p.clone());
            lights.push(i, kept(&light.probes)?);
            let camera = match kept(&image.seen[image.seen_by[i]?].probes)? {
                Kept::Plain(p) => Kept::Plain(reading(p, cfg, &units, true)),
                Kept::Detail(p) => Kept::Detail(reading(p, cfg, &units, true)),
            };
            cameras.push(i, camera);
        }
        let view = map_view::<F>(&light.lit[lit].maps, units.front_culled).ok()?;
        let seen = &image.seen[seen];
        let out = if k == 0 { &mut *pixels } else { &mut *others };
        let pass = Pass { image, view: &view, options: &options, seen: (seen.frame.ids(), seen.camera), out, setups };
        let done = if k == 0 {
            pass.run(units.map, &mut lights, &mut cameras, &mut camera_totals)
        } else {
            pass.run(units.map, &mut lights, &mut cameras, &mut umbra_core::NoProbe)
        };
        done.ok()?;
        let mut lights = lights.into_kept().into_iter();
        for (i, camera) in cameras.into_kept() {
            let (_, light) = lights.next()?;
            let names = (image.scene.name.as_str(), image.counts);
            costs[i] = Some(Ok(match (light, camera) {
                (Kept::Plain(l), Kept::Plain(c)) => report(names, cfg, &config, l, c),
                (Kept::Plain(l), Kept::Detail(c)) => report(names, cfg, &config, l, c),
                (Kept::Detail(l), Kept::Plain(c)) => report(names, cfg, &config, l, c),
                (Kept::Detail(l), Kept::Detail(c)) => report(names, cfg, &config, l, c),
            }));
        }
    }
    let metrics = compare_with(pixels, image.truth, &image.fields);
    let t = camera_totals;
    let tangent = ratio(t.tangent_setups, t.tangent_setups + t.trivial_pixels());
    Some((metrics, tangent, costs))
}

#[allow(clippy::cast_precision_loss, reason = "a ratio of pixel counts")]
fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

/// One shading of a configuration: the map it reads, the visibility it
/// shades and the buffers it writes.
struct Pass<'p, 'v, F: DepthFormat> {
    image: &'p ImageShare<'p>,
    view: &'p MapView<'v, F>,
    options: &'p CameraOptions,
    seen: (&'p [u32], Mat4),
    out: &'p mut Vec<Shaded>,
    setups: &'p mut Vec<ShadeSetup>,
}

impl<F: DepthFormat> Pass<'_, '_, F> {
    /// The silhouette pass, when the algorithm has one (its events to the
    /// light probes), then the shading (its events to the camera probes and
    /// to `also`).
    fn run<P: Probe>(
        self,
        map: MapKind,
        lights: &mut Probes,
        cameras: &mut Probes,
        also: &mut P,
    ) -> Result<(), RenderError> {
        match map {
            MapKind::Silhouette { packed: true } => self.silhouette::<Packed, P>(lights, cameras, also),
            MapKind::Silhouette { packed: false } => self.silhouette::<SilPoint, P>(lights, cameras, also),
            MapKind::Depth | MapKind::Volumes => self.shade(&MapUnit, cameras, also),
        }
    }

    fn silhouette<S: SilStore, P: Probe>(
        self,
        lights: &mut Probes,
        cameras: &mut Probes,
        also: &mut P,
    ) -> Result<(), RenderError> {
        let scene = self.image.scene;
        let light = scene.light().view_projection();
        let texels = lights
            .run(|fan| silhouette_map::<S, F, _>(&self.image.occluders, &light, self.view, self.options.shadow, fan))
            .map_err(PassError::from)?;
        let raster = self.view.raster();
        let sil = SilhouetteMap::view(raster.width(), raster.height(), &texels).map_err(PassError::from)?;
        self.shade(&SilhouetteUnit(&sil), cameras, also)
    }

    fn shade<U: ShadowUnit<F>, P: Probe>(
        self,
        unit: &U,
        cameras: &mut Probes,
        also: &mut P,
    ) -> Result<(), RenderError> {
        let Self { image, view, options, seen, out, setups } = self;
        cameras.run(|fan| shade(image.scene, seen, view, unit, options, &mut Tee(&mut *also, fan), out, setups))?;
        Ok(())
    }
}

/// Bytes an [`ImageShare`] holds beside its reference, at most, for an
/// image of `pixels` drawn in `tilings` tilings: each tiling's depth and
/// ids, and the reference's fields.
#[must_use]
pub const fn image_bytes(pixels: u64, tilings: u64) -> u64 {
    pixels * (8 * tilings + 32)
}

/// Bytes a [`LightShare`] holds, at most, for maps of `texels` texels
/// drawn in `tilings` tilings: two buffers of 4-byte texels each.
#[must_use]
pub const fn light_bytes(texels: u64, tilings: u64) -> u64 {
    texels * 8 * tilings
}

/// The shapes `archs` draw in, the default one first (for the memory a
/// share takes).
#[must_use]
pub fn tilings(archs: &[Arch]) -> usize {
    let mut shapes: Vec<Shape> = Vec::new();
    for a in archs.iter().filter(|a| shares(a)) {
        let s = shape(a);
        if s.tiling != Tiling::DEFAULT && !shapes.iter().any(|t| t.tiling == s.tiling) {
            shapes.push(s);
        }
    }
    shapes.len() + 1
}
