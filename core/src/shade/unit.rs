//! The shadow units the shading unit hands each pixel's lookup to: the
//! map's (the configured test and filter, with virtual samples; built with
//! every filter or fewer) and Sen et al.'s silhouette unit.

use core::marker::PhantomData;

use super::ShadeConfig;
use crate::depth::DepthFormat;
use crate::probe::Probe;
use crate::shadow::{
    AllFilters, Built, Lookup, MapCoord, MapView, Shadow, Slope, lookup, settle_region, virtual_samples,
};
use crate::silhouette::{SilStore, SilhouetteMap};

/// The unit that turns a pixel's lookup into its shadow fraction.
pub trait ShadowUnit<F: DepthFormat> {
    /// The datapaths the unit is built with: the shading unit leaves out
    /// what they do not need (the jittered filter's per-pixel footprint,
    /// smooth normals' tangent planes) and refuses a configuration they
    /// lack before it shades.
    type Built: Built;

    /// Decide one lookup against `map`; `tangent` solves the receiver's
    /// tangent plane on the map, for units that use virtual samples.
    fn decide<P: Probe, T: FnOnce() -> Option<Slope>>(
        &self,
        map: &MapView<'_, F>,
        cfg: &ShadeConfig,
        lookup: &Lookup,
        tangent: T,
        probe: &mut P,
    ) -> Shadow;

    /// The fraction [`decide`](Self::decide) gives every pixel of a block
    /// whose map positions lie in `[lo, hi]` and receiver depths in `z`
    /// (flat receivers), when the unit can settle them all at once without
    /// their own lookups; `None` otherwise (the default: each pixel is
    /// decided alone).
    fn settle(
        &self,
        _map: &MapView<'_, F>,
        _cfg: &ShadeConfig,
        _lo: [MapCoord; 2],
        _hi: [MapCoord; 2],
        _z: (i64, i64),
    ) -> Option<Shadow> {
        None
    }
}

/// The shadow unit of [`crate::shadow`]: the configured test and filter,
/// with Wang & Molnar's virtual samples when the configuration asks; built
/// with every filter.
pub type MapUnit = MapUnitWith<AllFilters>;

/// The [`MapUnit`](tyalias@MapUnit), as a value (`&MapUnit`, as of a unit struct).
#[allow(non_upper_case_globals, reason = "the value of the unit type of the same name")]
pub const MapUnit: MapUnit = MapUnitWith::new();

/// The map's shadow unit built with the datapaths `K` ([`crate::shadow::Built`]):
/// [`MapUnit`](tyalias@MapUnit) with all of them; `MapUnitWith::<BoxFilter>::new()` the box filter alone,
/// a constant bias and flat normals' tangent planes, and the code of no
/// other.
#[derive(Clone, Copy, Debug, Default)]
pub struct MapUnitWith<K: Built>(PhantomData<K>);

impl<K: Built> MapUnitWith<K> {
    /// The unit.
    #[must_use]
    pub const fn new() -> Self {
        Self(PhantomData)
    }
}

impl<F: DepthFormat, K: Built> ShadowUnit<F> for MapUnitWith<K> {
    type Built = K;

    fn decide<P: Probe, T: FnOnce() -> Option<Slope>>(
        &self,
        map: &MapView<'_, F>,
        cfg: &ShadeConfig,
        lookup: &Lookup,
        tangent: T,
        probe: &mut P,
    ) -> Shadow {
        decide_on_map::<F, P, T, K>(map, cfg, lookup, tangent, probe)
    }

    fn settle(
        &self,
        map: &MapView<'_, F>,
        cfg: &ShadeConfig,
        lo: [MapCoord; 2],
        hi: [MapCoord; 2],
        z: (i64, i64),
    ) -> Option<Shadow> {
        if K::BOX { settle_region(map, &cfg.shadow, lo, hi, z) } else { None }
    }
}

/// The map units' decision, with the datapaths `K`.
#[inline]
fn decide_on_map<F: DepthFormat, P: Probe, T: FnOnce() -> Option<Slope>, K: Built>(
    map: &MapView<'_, F>,
    cfg: &ShadeConfig,
    l: &Lookup,
    tangent: T,
    probe: &mut P,
) -> Shadow {
    if cfg.virtual_samples {
        virtual_samples::<F, P, K>(map, &cfg.shadow, l, tangent, probe)
    } else {
        lookup::<F, P, K>(map, &cfg.shadow, l, l.slope, probe)
    }
}

/// Sen et al.'s silhouette-map test ([`crate::silhouette`]) in place of the
/// filter: four corner tests, then the skewed quadrants.
#[derive(Debug)]
pub struct SilhouetteUnit<'s, 'a, S: SilStore>(pub &'s SilhouetteMap<'a, S>);

impl<F: DepthFormat, S: SilStore> ShadowUnit<F> for SilhouetteUnit<'_, '_, S> {
    type Built = AllFilters;

    fn decide<P: Probe, T: FnOnce() -> Option<Slope>>(
        &self,
        map: &MapView<'_, F>,
        cfg: &ShadeConfig,
        lookup: &Lookup,
        _tangent: T,
        probe: &mut P,
    ) -> Shadow {
        crate::silhouette::shadow(self.0, map, &cfg.shadow, lookup.x, lookup.y, lookup.z, probe)
    }
}
