//! A light's pass, drawn once per tiling for every configuration of one
//! [`LightKey`](super::LightKey).

use umbra_core::probe::{Probe, Totals};
use umbra_core::{DepthFormat, LightPassConfig, TileState};

use super::ImageShare;
use super::assign;
use super::probes::{Kept, Probes, Reporting};
use crate::base::maps::Tiling;
use crate::base::probes::Tee;
use crate::cost::arch::Arch;
use crate::cost::timing::PassKind;
use crate::pass::PassError;
use crate::pass::light::{Draw, LightMaps, LightOptions};
use crate::render::RenderConfig;
use crate::render::costed::shape;

/// One light pass, in one tiling, and what it left.
#[derive(Debug)]
pub(super) struct Lit<T> {
    /// The first pass (this one or an earlier) whose maps shade alike:
    /// the same texels and the same tile bounds.
    pub(super) class: usize,
    /// The first pass whose maps hold the same texels, whatever their
    /// tiles: one shading tests a lookup against each tiling's bounds.
    pub(super) texels: usize,
    pub(super) maps: LightMaps<T>,
}

/// What the configurations with one [`LightKey`](super::LightKey) share
/// of one light: its pass per tiling of the architectures (and the default
/// one), each architecture's light probe as its pass left it.
#[derive(Debug)]
pub(crate) struct LightShare<T> {
    /// The default tiling's first.
    pub(super) lit: Vec<Lit<T>>,
    /// For each architecture that [`shares`](super::shares), its entry in `lit`.
    pub(super) lit_by: Vec<Option<usize>>,
    pub(super) probes: Vec<(usize, Kept)>,
}

/// Whether two maps shade alike: the shadow unit reads their texels and
/// their tiles' bounds (to cull lookups), nothing else.
fn alike<T: PartialEq + Copy>(a: &LightMaps<T>, b: &LightMaps<T>) -> bool {
    let bounds = |t: &TileState<T>| [t.z1_min, t.z1_max, t.z2_min, t.z2_max];
    a.config.raster == b.config.raster
        && same_texels(a, b)
        && a.tiles.len() == b.tiles.len()
        && a.tiles.iter().zip(&b.tiles).all(|(x, y)| bounds(x) == bounds(y))
}

/// Whether two maps hold the same texels (in tiles of any side).
fn same_texels<T: PartialEq>(a: &LightMaps<T>, b: &LightMaps<T>) -> bool {
    let (ra, rb) = (a.config.raster, b.config.raster);
    (ra.width(), ra.height()) == (rb.width(), rb.height()) && a.z1 == b.z1 && a.z2 == b.z2
}

/// One light pass into new maps, as [`Reporting`].
struct Pass<'a, F: DepthFormat> {
    config: LightPassConfig,
    draws: &'a [Draw<'a>],
    options: LightOptions,
    totals: &'a mut Totals,
    format: core::marker::PhantomData<F>,
}

impl<F: DepthFormat> Reporting for Pass<'_, F> {
    type Out = Result<LightMaps<F::Texel>, PassError>;

    fn run<P: Probe>(self, probe: &mut P) -> Self::Out {
        LightMaps::draw::<F, _>(self.config, self.draws, self.options, Tee(self.totals, probe)).map(|(maps, _)| maps)
    }
}

impl<T: umbra_core::depth::Texel> LightShare<T> {
    /// The passes of light `light` of the scene (its index among the
    /// shadow-casting lights) for `cfg` (any configuration of its key) in
    /// format `F`: `None` when one cannot run or the light sees nothing,
    /// for each configuration to render (and fail) on its own.
    #[must_use]
    pub(crate) fn new<F: DepthFormat<Texel = T>>(
        image: &ImageShare<'_>,
        cfg: &RenderConfig,
        light: usize,
    ) -> Option<Self> {
        let scene: &crate::world::scene::Scene = &image.lit.get(light)?.scene;
        let units = cfg.algorithm.units::<F>(cfg.bias);
        let (shapes, lit_by) = assign(image.archs, (Tiling::DEFAULT, false), |a: &Arch| {
            let s = shape(a);
            (s.tiling, s.light_addresses)
        });
        let draws = scene.draws_culled(scene.light().view_projection(), |solid| units.cull(solid, cfg.culling));
        let (mut lit, mut kept, mut setups) = (Vec::<Lit<T>>::new(), Vec::new(), 0);
        for (k, &(tiling, detail)) in shapes.iter().enumerate() {
            let checked = cfg.check(image.scene, &image.limits).ok()?.targets(tiling.tile).ok()?;
            let mut probes = Probes::default();
            for (i, a) in image.archs.iter().enumerate().filter(|&(i, _)| lit_by[i] == Some(k)) {
                let pass = (PassKind::Light, checked.map);
                probes.push(i, Kept::new(a, pass, (cfg.format, units.unit.buffers()), detail));
            }
            let mut totals = Totals::default();
            let maps = probes
                .run(Pass::<F> {
                    config: LightPassConfig { raster: checked.map, unit: units.unit, max_z_cull: true },
                    draws: &draws,
                    options: LightOptions { per_draw: tiling.per_draw, ..LightOptions::default() },
                    totals: &mut totals,
                    format: core::marker::PhantomData,
                })
                .ok()?;
            kept.extend(probes.into_kept());
            if k == 0 {
                setups = totals.setups;
            }
            let class = lit.iter().position(|l| alike(&l.maps, &maps)).unwrap_or(k);
            let texels = lit.iter().position(|l| same_texels(&l.maps, &maps)).unwrap_or(k);
            lit.push(Lit { class, texels, maps });
        }
        kept.sort_by_key(|(i, _)| *i);
        (setups > 0).then_some(Self { lit, lit_by, probes: kept })
    }
}
