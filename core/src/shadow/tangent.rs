//! Tangent planes: the receiver's plane in light space, and the pass of virtual samples.

use super::{AllFilters, Built, Filter, Lookup, MapView, Shadow, ShadowConfig, Slope, lookup};
use crate::budget::PLANE_ONE;
use crate::config::RasterConfig;
use crate::depth::DepthFormat;
use crate::probe::{Event, Probe};

/// A receiver's tangent plane in light clip space, `π′ = M⁻ᵀ·(n, −n·p)`:
/// points on it satisfy `π′·(x, y, z, w) = 0` (Wang & Molnar 1994 §3.2:
/// the plane is moved to light space with the inverse transpose).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentPlane(pub [f64; 4]);

impl TangentPlane {
    /// The tangent plane at world point `p` with normal `n`, given the
    /// inverse transpose of the light's view-projection.
    #[must_use]
    pub fn new(p: glam::Vec3, n: glam::Vec3, light_inverse_transpose: &glam::Mat4) -> Self {
        let n = n.to_array().map(f64::from);
        let p = p.to_array().map(f64::from);
        let world = [n[0], n[1], n[2], -(n[0] * p[0] + n[1] * p[1] + n[2] * p[2])];
        let m = light_inverse_transpose.to_cols_array_2d();
        let mut out = [0.0; 4];
        for (r, o) in out.iter_mut().enumerate() {
            *o = (0..4).map(|c| f64::from(m[c][r]) * world[c]).sum();
        }
        Self(out)
    }

    /// The plane's depth slopes on the map, in format `F`'s [`PlaneZ`](crate::depth::PlaneZ) bits
    /// per texel: `z = −(A·x + B·y + D)/C` in NDC, with `x = 2u/W − 1` and
    /// `y = 1 − 2v/H`. `None` when the plane is (nearly) parallel to the
    /// light ray (`C → 0`): a slope of more than the whole depth range per
    /// texel, or nothing finite.
    #[must_use]
    pub fn slope<F: DepthFormat>(&self, raster: &RasterConfig) -> Option<Slope> {
        let [a, b, c, _] = self.0;
        let range = (F::SCALE as f64) * PLANE_ONE;
        let du = -a / c * 2.0 / f64::from(raster.width()) * range;
        let dv = b / c * 2.0 / f64::from(raster.height()) * range;
        let ok = |v: f64| v.is_finite() && v.abs() <= range;
        (ok(du) && ok(dv))
            .then(|| Slope { du: crate::round::round_ties_even(du), dv: crate::round::round_ties_even(dv) })
    }
}

/// Wang & Molnar's second pass for one pixel (§3.2's three rules): the
/// ordinary lookup first; when all nearby samples agree the pixel is decided
/// (trivially lit or shadowed); otherwise the receiver's tangent plane is set up (`setup`,
/// e.g. [`TangentPlane::slope`]) and the lookup repeated with virtual
/// samples — unless the plane is nearly parallel to the light ray (`setup`
/// gives `None`), when the ordinary result stands and the fallback is
/// reported.
#[inline]
pub fn shadow_with_virtual_samples<F: DepthFormat, P: Probe>(
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    l: &Lookup,
    setup: impl FnOnce() -> Option<Slope>,
    probe: &mut P,
) -> Shadow {
    virtual_samples::<F, P, AllFilters>(map, cfg, l, setup, probe)
}

/// [`shadow_with_virtual_samples`] on a unit built with the datapaths `K`.
#[inline]
pub(crate) fn virtual_samples<F: DepthFormat, P: Probe, K: Built>(
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    l: &Lookup,
    setup: impl FnOnce() -> Option<Slope>,
    probe: &mut P,
) -> Shadow {
    // "All nearby samples": the filter's own and the 2×2 texels around the
    // point, so that a lone sample (a point filter, or a jittered filter on
    // a footprint under a texel) is not taken as agreement with itself.
    let ordinary = lookup::<F, P, K>(map, cfg, l, None, probe);
    // Bilinear and boxes of 2 or more already read those texels.
    let covers_2x2 = matches!(cfg.filter, Filter::Bilinear) || matches!(cfg.filter, Filter::Box { size } if size >= 2);
    let around = || ShadowConfig { filter: Filter::Box { size: 2 }, ..*cfg };
    let agree = |s: Shadow| s == Shadow::ZERO || s == Shadow::ONE;
    if agree(ordinary) && (covers_2x2 || lookup::<F, P, K>(map, &around(), l, None, probe) == ordinary) {
        probe.event(Event::TrivialPixel { lit: ordinary == Shadow::ZERO });
        return ordinary;
    }
    probe.event(Event::TangentSetup);
    match setup() {
        Some(slope) => lookup::<F, P, K>(map, cfg, l, Some(slope), probe),
        None => {
            probe.event(Event::TangentFallback);
            ordinary
        }
    }
}
