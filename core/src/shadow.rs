//! The shadow unit: compare a surface point's light-space depth with the
//! map and filter the binary results — percentage-closer filtering
//! (Reeves, Salesin & Cook 1987 §2): compare first, then filter.
//!
//! # Depth tests
//! A sample is **shadowed** iff `z − bias > r`, where `z` is the point's
//! depth and `r` the texel's reference depth:
//!
//! | test | `r` | paper |
//! |---|---|---|
//! | [`DepthTest::First`] | `z1` | Williams 1978 |
//! | [`DepthTest::Second`] | `z2` (so `z ≤ z2` is lit: planar two-sided surfaces work) | Wang & Molnar 1994 §3.1 |
//! | [`DepthTest::Midpoint`] | `(z1 + z2) / 2` | Woo 1992, via Weiskopf & Ertl 2003 §3 |
//! | [`DepthTest::Dual`] | `z1 + min((z2 − z1) / 2, offset)` | Weiskopf & Ertl 2003 §4 |
//!
//! The receiver's depth (less the bias) is rounded to the map's format as
//! the light pass rounds fragments, so a receiver exactly on a stored
//! surface compares equal; references are formed from the widened texels in
//! [`PlaneZ`] bits (so the midpoint keeps its half LSB). The bias is
//! constant or, as Reeves' `[Bias0, Bias1]`, drawn per sample.
//!
//! # Virtual samples
//! With a [`Slope`], each sample compares the receiver's tangent plane at
//! that texel's centre instead of one depth (Wang & Molnar 1994 §3.2),
//! evaluated once per footprint row and stepped by forward differences.
//! [`shadow_with_virtual_samples`] is their second pass for one pixel.
//!
//! # Filters
//! Map coordinates are texels with 16 fraction bits ([`MapCoord`]); texel
//! `(i, j)` covers `[i, i + 1) × [j, j + 1)`. [`Filter::Point`] reads the
//! texel under the point; [`Filter::Bilinear`] the four nearest texel
//! centres, weighted by the fractional position; [`Filter::Box`] the `n × n`
//! texels centred on the point; [`Filter::Jittered`] Reeves' stochastic
//! filter (Figure 4): the footprint, enlarged by `ResFactor` and at least
//! `MinSize`, is split into `ns × nt` subregions (`NumSamples`,
//! `MinSamples`) sampled with jitter from a seeded PCG generator, each
//! sample with its own bias. Samples outside the map are lit, and a point
//! nearer than the near plane (`z < 0`, which includes behind the light)
//! is lit.
//!
//! # Culling lookups
//! Before any texel is read, the tiles under the footprint are consulted:
//! when their stored min/max prove that every sample agrees (all lit, or —
//! with the whole footprint inside the map — all shadowed), no texel is
//! read and the skip is reported (Reeves et al. 1987 §3.3's per-tile max z).
//! The result is exactly the one the samples would give.

use core::fmt;

use fixed::types::{I16F16, U16F16};

use crate::config::RasterConfig;
use crate::depth::{DepthFormat, PLANE_FRACTION_BITS, PlaneZ};
use crate::probe::{Buffer, Event, Probe, TexelRead};
use crate::tile::TileRect;
use crate::zbuffer::TileState;

/// A position on the map in texels, 16 fraction bits.
pub type MapCoord = I16F16;

/// The fraction of a lookup in shadow: 0 lit, 1 fully shadowed.
pub type Shadow = U16F16;

/// Half a texel.
const HALF: MapCoord = MapCoord::from_bits(1 << 15);

/// Which reference depth a sample compares against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthTest {
    /// Nearest depth `z1`.
    First,
    /// Second-nearest depth `z2`: from the dual unit, or the single buffer
    /// of a front-face-culled pass ([`MapView::front_culled`]).
    Second,
    /// Woo's midpoint `(z1 + z2) / 2`.
    Midpoint,
    /// Weiskopf & Ertl's dual depth `z1 + min((z2 − z1) / 2, offset)`.
    Dual {
        /// The largest distance above `z1`, in [`PlaneZ`] (format LSBs).
        offset: PlaneZ,
    },
}

impl DepthTest {
    /// Whether the test reads `z2`.
    #[must_use]
    pub const fn needs_z2(self) -> bool {
        !matches!(self, Self::First)
    }

    /// Whether the test reads `z1`.
    #[must_use]
    pub const fn needs_z1(self) -> bool {
        !matches!(self, Self::Second)
    }

    /// The reference depth from `z1` and `z2` ([`PlaneZ`] bits). Monotonic
    /// in both, so tile bounds bound it.
    #[inline]
    fn reference(self, z1: i64, z2: i64) -> i64 {
        match self {
            Self::First => z1,
            Self::Second => z2,
            Self::Midpoint => (z1 >> 1) + (z2 >> 1) + (z1 & z2 & 1),
            Self::Dual { offset } => z1.saturating_add(((z2 - z1) >> 1).min(offset.to_bits().max(0))),
        }
    }
}

/// The depth bias, in [`PlaneZ`] (format LSBs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bias {
    /// The same for every sample.
    Constant(PlaneZ),
    /// Drawn uniformly per sample from `[lo, hi]` (Reeves' `Bias0`, `Bias1`).
    Range {
        /// `Bias0`.
        lo: PlaneZ,
        /// `Bias1`.
        hi: PlaneZ,
    },
}

impl Default for Bias {
    /// No bias: Wang & Molnar's default for second depth.
    fn default() -> Self {
        Self::ZERO
    }
}

impl Bias {
    /// No bias.
    pub const ZERO: Self = Self::Constant(PlaneZ::ZERO);

    /// The smallest and largest bias a sample can get.
    #[must_use]
    pub fn bounds(self) -> (i64, i64) {
        match self {
            Self::Constant(b) => (b.to_bits(), b.to_bits()),
            Self::Range { lo, hi } => (lo.to_bits(), hi.to_bits()),
        }
    }
}

/// Reeves' stochastic filter parameters (Figure 4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Jitter {
    /// `NumSamples`: samples per lookup (before the per-axis clamps).
    pub num_samples: u16,
    /// `ResFactor`: enlarges the footprint (softer shadows).
    pub res_factor: MapCoord,
    /// `MinSamples`: fewest samples along each axis.
    pub min_samples: u16,
    /// `MinSize`: smallest half-size of the sampled region, texels.
    pub min_size: MapCoord,
}

impl Jitter {
    /// The values Reeves et al. list in Figure 4.
    pub const REEVES: Self =
        Self { num_samples: 16, res_factor: MapCoord::lit("3"), min_samples: 1, min_size: MapCoord::ZERO };
}

/// How the binary comparisons of a lookup are combined.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Filter {
    /// The texel under the point.
    Point,
    /// The four nearest texel centres, weighted by the fractional position.
    Bilinear,
    /// `size × size` texels centred on the point, equally weighted.
    Box {
        /// Side in texels, `1..=16`.
        size: u8,
    },
    /// Reeves' jittered stochastic sampling of the footprint.
    Jittered(Jitter),
}

/// A validated shadow-unit configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ShadowConfig {
    test: DepthTest,
    bias: Bias,
    filter: Filter,
    cull_lookups: bool,
}

/// A shadow configuration the unit cannot use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ShadowConfigError {
    /// A box filter side outside `1..=16`.
    BoxSize {
        /// The side asked for.
        size: u8,
    },
    /// `NumSamples` outside `1..=256`, or `MinSamples` above it or zero.
    Samples {
        /// `NumSamples`.
        num_samples: u16,
        /// `MinSamples`.
        min_samples: u16,
    },
    /// A negative `ResFactor` or `MinSize`.
    Region,
    /// A bias range with `lo > hi`.
    BiasRange,
    /// A negative dual-depth offset.
    Offset,
}

impl fmt::Display for ShadowConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BoxSize { size } => write!(f, "box filter size {size} is outside 1..=16"),
            Self::Samples { num_samples, min_samples } => {
                write!(f, "NumSamples {num_samples} must be in 1..=256 and MinSamples {min_samples} in 1..=NumSamples")
            }
            Self::Region => write!(f, "ResFactor and MinSize must not be negative"),
            Self::BiasRange => write!(f, "bias range has Bias0 > Bias1"),
            Self::Offset => write!(f, "dual-depth offset must not be negative"),
        }
    }
}

impl core::error::Error for ShadowConfigError {}

impl ShadowConfig {
    /// Validate a configuration. `cull_lookups` enables per-tile culling.
    ///
    /// # Errors
    /// See [`ShadowConfigError`].
    pub fn new(test: DepthTest, bias: Bias, filter: Filter, cull_lookups: bool) -> Result<Self, ShadowConfigError> {
        match filter {
            Filter::Box { size } if !(1..=16).contains(&size) => return Err(ShadowConfigError::BoxSize { size }),
            Filter::Jittered(j) => {
                if !(1..=256).contains(&j.num_samples) || j.min_samples == 0 || j.min_samples > j.num_samples {
                    return Err(ShadowConfigError::Samples { num_samples: j.num_samples, min_samples: j.min_samples });
                }
                if j.res_factor < 0 || j.min_size < 0 {
                    return Err(ShadowConfigError::Region);
                }
            }
            _ => {}
        }
        if let Bias::Range { lo, hi } = bias
            && lo > hi
        {
            return Err(ShadowConfigError::BiasRange);
        }
        if let DepthTest::Dual { offset } = test
            && offset < 0
        {
            return Err(ShadowConfigError::Offset);
        }
        Ok(Self { test, bias, filter, cull_lookups })
    }

    /// The depth test.
    #[must_use]
    pub const fn test(&self) -> DepthTest {
        self.test
    }

    /// The filter.
    #[must_use]
    pub const fn filter(&self) -> Filter {
        self.filter
    }

    /// The bias.
    #[must_use]
    pub const fn bias(&self) -> Bias {
        self.bias
    }

    /// Whether a lookup draws random numbers (the jittered filter's
    /// positions, or a bias range's per-sample bias): only then does its
    /// [`Lookup::seed`] matter.
    #[must_use]
    pub const fn draws_random(&self) -> bool {
        matches!(self.filter, Filter::Jittered(_)) || matches!(self.bias, Bias::Range { .. })
    }

    /// The same configuration with lookup culling on or off.
    #[must_use]
    pub const fn with_cull_lookups(self, cull_lookups: bool) -> Self {
        Self { cull_lookups, ..self }
    }
}

/// A light pass's maps, as the shadow unit reads them.
#[derive(Clone, Copy, Debug)]
pub struct MapView<'a, F: DepthFormat> {
    raster: RasterConfig,
    z1: &'a [F::Texel],
    z2: &'a [F::Texel],
    tiles: &'a [TileState<F::Texel>],
    /// Tiles in a row of the map.
    across: usize,
    /// The second depth is the single buffer of a front-face-culled pass.
    second_in_z1: bool,
}

impl<'a, F: DepthFormat> MapView<'a, F> {
    /// The map's raster configuration.
    #[must_use]
    pub const fn raster(&self) -> &RasterConfig {
        &self.raster
    }

    /// View finished maps. `z2` may be empty when no test reads it.
    ///
    /// # Errors
    /// [`crate::ConfigError::BufferLength`] naming a buffer of the wrong length.
    pub fn new(
        raster: RasterConfig,
        z1: &'a [F::Texel],
        z2: &'a [F::Texel],
        tiles: &'a [TileState<F::Texel>],
    ) -> Result<Self, crate::ConfigError> {
        let texels = raster.texel_count();
        let wrong = |buffer, expected, found| crate::ConfigError::BufferLength { buffer, expected, found };
        if z1.len() != texels {
            return Err(wrong("z1", texels, z1.len()));
        }
        if !z2.is_empty() && z2.len() != texels {
            return Err(wrong("z2", texels, z2.len()));
        }
        if tiles.len() != raster.tile_count() {
            return Err(wrong("tiles", raster.tile_count(), tiles.len()));
        }
        Ok(Self { raster, z1, z2, tiles, across: raster.tiles().0 as usize, second_in_z1: false })
    }

    /// View the map of a single-depth pass with front-face culling: its one
    /// buffer holds the second depth (Wang & Molnar 1994 §3.4), which
    /// [`DepthTest::Second`] then reads (so do the tests that need `z1`:
    /// there is no first depth in such a map).
    ///
    /// # Errors
    /// [`crate::ConfigError::BufferLength`] naming a buffer of the wrong length.
    pub fn front_culled(
        raster: RasterConfig,
        z: &'a [F::Texel],
        tiles: &'a [TileState<F::Texel>],
    ) -> Result<Self, crate::ConfigError> {
        Ok(Self { second_in_z1: true, ..Self::new(raster, z, &[], tiles)? })
    }

    /// Texel `(x, y)` of `buf` widened to [`PlaneZ`] bits; the far value
    /// when `buf` is empty (no second depth: nothing behind).
    #[inline]
    fn texel(&self, buf: &[F::Texel], x: u32, y: u32) -> i64 {
        let i = y as usize * self.raster.width() as usize + x as usize;
        F::widen(buf.get(i).copied().unwrap_or(F::FAR))
    }

    /// One sample: whether a receiver at depth `z` less `bias` ([`PlaneZ`]
    /// bits), rounded to the map's format, lies behind the test's reference
    /// at texel `(x, y)`, the texels read reported to probes that ask;
    /// `None` outside the map (lit, nothing read).
    #[inline]
    pub(crate) fn sample<P: Probe>(
        &self,
        test: DepthTest,
        (x, y): (i64, i64),
        z: i64,
        bias: i64,
        probe: &mut P,
    ) -> Option<bool> {
        let (x, y) = (u32::try_from(x).ok()?, u32::try_from(y).ok()?);
        if x >= self.raster.width() || y >= self.raster.height() {
            return None;
        }
        Some(self.compare(test, x, y, at_format::<F>(z.saturating_sub(bias)), probe))
    }

    /// The sample of texel `(x, y)`, inside the map, for a receiver already
    /// biased and rounded to the map's format: whether it lies behind the
    /// test's reference, the texels read reported to probes that ask.
    #[inline]
    fn compare<P: Probe>(&self, test: DepthTest, x: u32, y: u32, receiver: i64, probe: &mut P) -> bool {
        if P::TEXELS {
            for buffer in self.buffers_read(test) {
                probe.texel_read(TexelRead { buffer, x, y });
            }
        }
        receiver > self.reference(test, x, y)
    }

    /// The buffers a test reads from this map (one, or both).
    pub(crate) fn buffers_read(&self, test: DepthTest) -> impl Iterator<Item = Buffer> {
        let z1 = test.needs_z1() || (test.needs_z2() && self.second_in_z1);
        let z2 = test.needs_z2() && !self.second_in_z1;
        [(z1, Buffer::Z1), (z2, Buffer::Z2)].into_iter().filter_map(|(read, b)| read.then_some(b))
    }

    /// A tile's stored bounds of the second depth: `z2`'s, the single
    /// buffer's in a front-face-culled map, the far value when there is none.
    #[inline]
    fn second_bounds(&self, t: &TileState<F::Texel>) -> (F::Texel, F::Texel) {
        if self.second_in_z1 {
            (t.z1_min, t.z1_max)
        } else if self.z2.is_empty() {
            (F::FAR, F::FAR)
        } else {
            (t.z2_min, t.z2_max)
        }
    }

    fn reference(&self, test: DepthTest, x: u32, y: u32) -> i64 {
        let z1 = if test.needs_z1() { self.texel(self.z1, x, y) } else { 0 };
        let second = if self.second_in_z1 { self.z1 } else { self.z2 };
        let z2 = if test.needs_z2() { self.texel(second, x, y) } else { 0 };
        test.reference(z1, z2)
    }
}

/// One lookup: a surface point in light space and its footprint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lookup {
    /// Column on the map, texels.
    pub x: MapCoord,
    /// Row on the map (down), texels.
    pub y: MapCoord,
    /// Light-space depth of the point.
    pub z: PlaneZ,
    /// Half-size of the pixel's footprint on the map, texels (for the
    /// jittered filter; Reeves' `sres`, `tres` in texels).
    pub footprint: [MapCoord; 2],
    /// Seed of this lookup's random numbers (the same seed, the same result).
    pub seed: u64,
    /// The receiver's tangent plane, when each sample compares its own
    /// depth (Wang & Molnar's virtual samples); `None` compares `z`.
    pub slope: Option<Slope>,
}

/// A receiver's tangent plane on the map: its depth rises by `du` per texel
/// to the right and `dv` per texel down ([`PlaneZ`] bits), through the
/// lookup's point. Wang & Molnar 1994 §3.2: "virtual samples".
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Slope {
    /// Depth step per texel to the right.
    pub du: i64,
    /// Depth step per texel down.
    pub dv: i64,
}

/// `a · b / 2¹⁶`, floored, saturated to `i64`.
#[inline]
pub(crate) fn mul_shift(a: i64, b: i64) -> i64 {
    crate::round::saturate((i128::from(a) * i128::from(b)) >> 16)
}

impl Lookup {
    /// The receiver's depth at the centre of texel `(x, y)`, evaluated
    /// directly: `z + ⌊du·Δu⌋ + ⌊dv·Δv⌋` with `Δu`, `Δv` the centre's offset
    /// from the point in 2⁻¹⁶ texels. Without a slope, `z`. Stepping one
    /// texel adds exactly `du` (or `dv`): the filters step by forward
    /// differences and get these same bits.
    #[must_use]
    pub fn depth_at(&self, x: i32, y: i32) -> i64 {
        self.depth_on(self.slope, x, y)
    }

    /// [`Lookup::depth_at`] for the receiver with slope `slope`.
    fn depth_on(&self, slope: Option<Slope>, x: i32, y: i32) -> i64 {
        let z = self.z.to_bits();
        let Some(s) = slope else { return z };
        let centre = |t: i32, p: MapCoord| (i64::from(t) << 16) + (1 << 15) - i64::from(p.to_bits());
        z.saturating_add(mul_shift(s.du, centre(x, self.x))).saturating_add(mul_shift(s.dv, centre(y, self.y)))
    }
}

/// An integer rectangle of texels, inclusive, possibly outside the map.
#[derive(Clone, Copy, Debug)]
struct Texels {
    x0: i32,
    y0: i32,
    x1: i32,
    y1: i32,
}

/// Whole texels of a map coordinate (floor).
#[inline]
fn floor(c: MapCoord) -> i32 {
    c.to_bits() >> 16
}

impl Texels {
    /// The texels a filter reads around a lookup (for the jittered filter,
    /// its sample `grid`); `None` for a jittered filter without one.
    #[inline]
    fn under(filter: Filter, l: &Lookup, grid: Option<([MapCoord; 2], [u32; 2])>) -> Option<Self> {
        Some(match (filter, grid) {
            (Filter::Point, _) => Self { x0: floor(l.x), y0: floor(l.y), x1: floor(l.x), y1: floor(l.y) },
            (Filter::Bilinear, _) => {
                let (x, y) = (floor(l.x.saturating_sub(HALF)), floor(l.y.saturating_sub(HALF)));
                Self { x0: x, y0: y, x1: x + 1, y1: y + 1 }
            }
            (Filter::Box { size }, _) => {
                // First texel: floor(x − (n − 1)/2), the n texel centres nearest x.
                let n = i32::from(size);
                let back = MapCoord::from_bits((n - 1) << 15);
                let (x, y) = (floor(l.x.saturating_sub(back)), floor(l.y.saturating_sub(back)));
                Self { x0: x, y0: y, x1: x + n - 1, y1: y + n - 1 }
            }
            (Filter::Jittered(_), Some((half, _))) => Self {
                x0: floor(l.x.saturating_sub(half[0])),
                y0: floor(l.y.saturating_sub(half[1])),
                x1: floor(l.x.saturating_add(half[0])),
                y1: floor(l.y.saturating_add(half[1])),
            },
            (Filter::Jittered(_), None) => return None,
        })
    }

    fn count(&self) -> u32 {
        let side = |a: i32, b: i32| (i64::from(b) - i64::from(a) + 1).unsigned_abs();
        u32::try_from(side(self.x0, self.x1) * side(self.y0, self.y1)).unwrap_or(u32::MAX)
    }

    /// The part inside a `w × h` map, if any, and whether all of it is inside.
    #[inline]
    fn clip(&self, w: u32, h: u32) -> (Option<TileRect>, bool) {
        let (w, h) = (i32::try_from(w).unwrap_or(i32::MAX), i32::try_from(h).unwrap_or(i32::MAX));
        let inside = self.x0 >= 0 && self.y0 >= 0 && self.x1 < w && self.y1 < h;
        let (x0, y0, x1, y1) = (self.x0.max(0), self.y0.max(0), self.x1.min(w - 1), self.y1.min(h - 1));
        if x0 > x1 || y0 > y1 {
            return (None, inside);
        }
        let r = TileRect {
            x0: x0.unsigned_abs(),
            y0: y0.unsigned_abs(),
            x1: x1.unsigned_abs() + 1,
            y1: y1.unsigned_abs() + 1,
        };
        (Some(r), inside)
    }
}

/// Reeves' sample grid for a footprint (Figure 4): the sampled region's
/// half-sizes in texels (footprint × `ResFactor`, at least `MinSize`) and
/// the number of samples along each axis.
#[must_use]
pub fn jitter_grid(j: &Jitter, footprint: [MapCoord; 2]) -> ([MapCoord; 2], [u32; 2]) {
    let half = footprint.map(|f| f.saturating_abs().saturating_mul(j.res_factor).max(j.min_size));
    let n = u32::from(j.num_samples);
    let (lo, hi) = (u32::from(j.min_samples), n);
    let round = |v: U16F16| v.saturating_add(U16F16::from_bits(1 << 15)).to_num::<u32>();
    let unsigned = |v: MapCoord| U16F16::from_bits(v.to_bits().unsigned_abs());
    let (s, t) = (unsigned(half[0]), unsigned(half[1]));
    let area4 = s.saturating_mul(t).saturating_mul_int(4);
    let counts = if area4 < U16F16::saturating_from_num(n) {
        [round(s.saturating_mul_int(2)).clamp(lo, hi), round(t.saturating_mul_int(2)).clamp(lo, hi)]
    } else {
        // nt = sqrt(tres · N / sres) + ½, then ns = N / nt + ½ (both clamped).
        // A long, thin footprint saturates the ratio: `nt` is then clamped.
        let ratio = t.saturating_mul_int(n).saturating_div(s.max(U16F16::DELTA));
        let nt = ((u64::from(ratio.to_bits()) << 16).isqrt() + (1 << 15)) >> 16;
        let nt = u32::try_from(nt).unwrap_or(hi).clamp(lo, hi);
        let ns = ((2 * n + nt) / (2 * nt)).clamp(lo, hi);
        [ns, nt]
    };
    (half, counts)
}

/// Shadow a lookup: the fraction of its samples in shadow.
pub fn shadow<F: DepthFormat, P: Probe>(map: &MapView<'_, F>, cfg: &ShadowConfig, l: &Lookup, probe: &mut P) -> Shadow {
    lookup(map, cfg, l, l.slope, probe)
}

/// [`shadow`] with the receiver's slope given apart from the lookup (a
/// pixel's ordinary and virtual-sample lookups share the rest). The front
/// of the unit (footprint, clip, the tile-bounds cull) decides most lookups
/// on its own; the filter runs for the rest.
#[inline(always)]
fn lookup<F: DepthFormat, P: Probe>(
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    l: &Lookup,
    slope: Option<Slope>,
    probe: &mut P,
) -> Shadow {
    if l.z < 0 {
        return Shadow::ZERO;
    }
    let grid = match cfg.filter {
        Filter::Jittered(j) => Some(jitter_grid(&j, l.footprint)),
        _ => None,
    };
    let Some(footprint) = Texels::under(cfg.filter, l, grid) else { return Shadow::ZERO };
    let (inside_map, whole) = footprint.clip(map.raster.width(), map.raster.height());
    let Some(inside_map) = inside_map else {
        // Entirely outside the map: lit, and nothing to read.
        probe.event(Event::LookupCulled { texels: footprint.count() });
        return Shadow::ZERO;
    };
    if cfg.cull_lookups {
        let (bias_lo, bias_hi) = cfg.bias.bounds();
        // The receiver's depth range over the footprint: a plane takes its
        // extremes at the corners (a receiver without a slope is one depth).
        let (z_lo, z_hi) = if slope.is_some() {
            let corners = [
                (footprint.x0, footprint.y0),
                (footprint.x1, footprint.y0),
                (footprint.x0, footprint.y1),
                (footprint.x1, footprint.y1),
            ]
            .map(|(x, y)| l.depth_on(slope, x, y));
            (corners.iter().copied().min().unwrap_or(0), corners.iter().copied().max().unwrap_or(0))
        } else {
            (l.z.to_bits(), l.z.to_bits())
        };
        let (r_lo, r_hi) = reference_bounds(map, cfg.test, &inside_map);
        if at_format::<F>(z_hi.saturating_sub(bias_lo)) <= r_lo {
            probe.event(Event::LookupCulled { texels: footprint.count() });
            return Shadow::ZERO;
        }
        if whole && at_format::<F>(z_lo.saturating_sub(bias_hi)) > r_hi {
            probe.event(Event::LookupCulled { texels: footprint.count() });
            return Shadow::ONE;
        }
    }
    if let (Filter::Box { .. }, true, None, Bias::Constant(b)) = (cfg.filter, whole, slope, cfg.bias) {
        return uniform_box(
            map,
            cfg.test,
            &inside_map,
            at_format::<F>(l.z.to_bits().saturating_sub(b.to_bits())),
            probe,
        );
    }
    filter(map, cfg, &Lookup { slope, ..*l }, footprint, grid, probe)
}

/// The commonest filter, inline: a box all on the map against one receiver
/// depth, already biased and rounded, so that each texel is a compare.
#[inline]
fn uniform_box<F: DepthFormat, P: Probe>(
    map: &MapView<'_, F>,
    test: DepthTest,
    r: &TileRect,
    receiver: i64,
    probe: &mut P,
) -> Shadow {
    let mut count = 0u64;
    for y in r.y0..r.y1 {
        for x in r.x0..r.x1 {
            count += u64::from(map.compare(test, x, y, receiver, probe));
        }
    }
    let reads = r.area();
    report_reads(map, test, reads, false, probe);
    fraction(count, u64::from(reads))
}

/// Report a lookup's `reads` texels read from each buffer its test reads,
/// and whether they were virtual samples.
#[inline]
fn report_reads<F: DepthFormat, P: Probe>(
    map: &MapView<'_, F>,
    test: DepthTest,
    reads: u32,
    virtual_samples: bool,
    probe: &mut P,
) {
    if reads == 0 {
        return;
    }
    if virtual_samples {
        probe.event(Event::VirtualSamples { count: reads });
    }
    for buffer in map.buffers_read(test) {
        probe.event(Event::MapRead { buffer, texels: reads, bytes: reads * F::KIND.bytes() });
    }
}

/// The filter: the samples of a lookup the front did not decide, over its
/// footprint (inclusive; samples off the map are lit).
#[inline(never)]
fn filter<F: DepthFormat, P: Probe>(
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    l: &Lookup,
    footprint: Texels,
    grid: Option<([MapCoord; 2], [u32; 2])>,
    probe: &mut P,
) -> Shadow {
    let mut rng = oorandom::Rand32::new(l.seed);
    let mut reads = 0u32;
    let mut sample = |x: i32, y: i32, z: i64, rng: &mut oorandom::Rand32| -> bool {
        let bias = match cfg.bias {
            Bias::Constant(b) => b.to_bits(),
            Bias::Range { lo, hi } => lerp_bits(lo.to_bits(), hi.to_bits(), rng.rand_u32()),
        };
        let shadowed = map.sample(cfg.test, (x.into(), y.into()), z, bias, probe);
        reads += u32::from(shadowed.is_some());
        shadowed.unwrap_or(false)
    };
    let result = match (cfg.filter, grid) {
        (Filter::Point, _) => {
            let (x, y) = (footprint.x0, footprint.y0);
            Shadow::from_num(u8::from(sample(x, y, l.depth_at(x, y), &mut rng)))
        }
        (Filter::Bilinear, _) => {
            // Weights from the fractional position, 16 bits each: they sum to 2³² exactly.
            let fx = u64::from(l.x.saturating_sub(HALF).frac().to_bits().unsigned_abs());
            let fy = u64::from(l.y.saturating_sub(HALF).frac().to_bits().unsigned_abs());
            let one = 1u64 << 16;
            let weights = [(one - fx) * (one - fy), fx * (one - fy), (one - fx) * fy, fx * fy];
            // The receiver at the four centres by forward differences.
            let z00 = l.depth_at(footprint.x0, footprint.y0);
            let (du, dv) = l.slope.map_or((0, 0), |s| (s.du, s.dv));
            let z = [z00, z00.saturating_add(du), z00.saturating_add(dv), z00.saturating_add(du).saturating_add(dv)];
            let corners = [(0, 0), (1, 0), (0, 1), (1, 1)];
            let shadowed: u64 = corners
                .iter()
                .zip(weights)
                .zip(z)
                .map(
                    |((&(dx, dy), wgt), z)| {
                        if sample(footprint.x0 + dx, footprint.y0 + dy, z, &mut rng) { wgt } else { 0 }
                    },
                )
                .sum();
            fraction(shadowed, 1 << 32)
        }
        (Filter::Box { .. }, _) => {
            let mut count = 0u64;
            // One evaluation per row, then forward differences along it
            // (the box all on the map against one depth is `uniform_box`).
            let du = l.slope.map_or(0, |s| s.du);
            for y in footprint.y0..=footprint.y1 {
                let mut z = l.depth_at(footprint.x0, y);
                for x in footprint.x0..=footprint.x1 {
                    count += u64::from(sample(x, y, z, &mut rng));
                    z = z.saturating_add(du);
                }
            }
            fraction(count, u64::from(footprint.count()))
        }
        (Filter::Jittered(_), Some((half, [ns, nt]))) => {
            // Subregions of 2·half/n texels; each sample jittered within its own.
            let step = |h: MapCoord, n: u32| {
                MapCoord::from_bits(h.to_bits().saturating_mul(2) / i32::try_from(n.max(1)).unwrap_or(i32::MAX))
            };
            let (ds, dt) = (step(half[0], ns), step(half[1], nt));
            let s0 = l.x.saturating_sub(half[0]).saturating_add(ds / 2);
            let t0 = l.y.saturating_sub(half[1]).saturating_add(dt / 2);
            let mut count = 0u64;
            for i in 0..ns {
                for j in 0..nt {
                    let s = s0.saturating_add(ds.saturating_mul_int(i32::try_from(i).unwrap_or(i32::MAX)));
                    let t = t0.saturating_add(dt.saturating_mul_int(i32::try_from(j).unwrap_or(i32::MAX)));
                    let ju = jitter(ds / 2, rng.rand_u32());
                    let jv = jitter(dt / 2, rng.rand_u32());
                    // Jittered texels are irregular: the plane is evaluated directly.
                    let (u, v) = (floor(s.saturating_add(ju)), floor(t.saturating_add(jv)));
                    count += u64::from(sample(u, v, l.depth_at(u, v), &mut rng));
                }
            }
            fraction(count, u64::from(ns * nt))
        }
        (Filter::Jittered(_), None) => Shadow::ZERO,
    };
    report_reads(map, cfg.test, reads, l.slope.is_some(), probe);
    result
}

/// A receiver depth rounded to the map's format (as the light pass rounds
/// fragments), widened back: comparisons are at the stored precision, so a
/// receiver exactly on a stored surface compares equal.
#[inline]
fn at_format<F: DepthFormat>(z: i64) -> i64 {
    F::widen(F::texel(PlaneZ::from_bits(z)))
}

/// `k / n` as a [`Shadow`], rounded to nearest.
fn fraction(k: u64, n: u64) -> Shadow {
    let n = n.max(1);
    let bits = ((k << 16) + n / 2) / n;
    Shadow::from_bits(u32::try_from(bits.min(1 << 16)).unwrap_or(1 << 16))
}

/// A uniform offset in `[−half, half)` from 32 random bits.
fn jitter(half: MapCoord, r: u32) -> MapCoord {
    let signed = i64::from(r) - (1 << 31); // [−2³¹, 2³¹)
    let v = (i64::from(half.to_bits()) * signed) >> 31;
    MapCoord::from_bits(i32::try_from(v).unwrap_or(0))
}

/// `lo + (hi − lo)·r/2³²` in [`PlaneZ`] bits.
fn lerp_bits(lo: i64, hi: i64, r: u32) -> i64 {
    let span = i128::from(hi) - i128::from(lo);
    let v = i128::from(lo) + ((span * i128::from(r)) >> 32);
    i64::try_from(v).unwrap_or(lo)
}

/// The smallest and largest reference depth over the tiles under `r`, from
/// their stored bounds. A test that reads one buffer takes that buffer's
/// bounds; the others combine both per tile.
#[inline]
fn reference_bounds<F: DepthFormat>(map: &MapView<'_, F>, test: DepthTest, r: &TileRect) -> (i64, i64) {
    match test {
        DepthTest::First => over_tiles(map, r, |t| (F::widen(t.z1_min), F::widen(t.z1_max))),
        DepthTest::Second => over_tiles(map, r, |t| {
            let (z2_min, z2_max) = map.second_bounds(t);
            (F::widen(z2_min), F::widen(z2_max))
        }),
        _ => over_tiles(map, r, |t| {
            let (z2_min, z2_max) = map.second_bounds(t);
            (test.reference(F::widen(t.z1_min), F::widen(z2_min)), test.reference(F::widen(t.z1_max), F::widen(z2_max)))
        }),
    }
}

/// The smallest and largest of `bounds` over the stored state of every
/// tile under `r` (most footprints lie in one tile: it is read alone).
#[inline(always)]
fn over_tiles<F: DepthFormat>(
    map: &MapView<'_, F>,
    r: &TileRect,
    bounds: impl Fn(&TileState<F::Texel>) -> (i64, i64),
) -> (i64, i64) {
    let shift = map.raster.tile_shift();
    let (tx0, tx1) = ((r.x0 >> shift) as usize, ((r.x1 - 1) >> shift) as usize);
    let (ty0, ty1) = ((r.y0 >> shift) as usize, ((r.y1 - 1) >> shift) as usize);
    if tx0 == tx1 && ty0 == ty1 {
        return map.tiles.get(ty0 * map.across + tx0).map_or((i64::MAX, i64::MIN), bounds);
    }
    let (mut lo, mut hi) = (i64::MAX, i64::MIN);
    for ty in ty0..=ty1 {
        let row = ty * map.across;
        for t in map.tiles.get(row + tx0..=row + tx1).unwrap_or_default() {
            let (a, b) = bounds(t);
            (lo, hi) = (lo.min(a), hi.max(b));
        }
    }
    (lo, hi)
}

const _: () = assert!(PLANE_FRACTION_BITS == 32, "texels widen by a 32-bit shift");

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

    /// The plane's depth slopes on the map, in format `F`'s [`PlaneZ`] bits
    /// per texel: `z = −(A·x + B·y + D)/C` in NDC, with `x = 2u/W − 1` and
    /// `y = 1 − 2v/H`. `None` when the plane is (nearly) parallel to the
    /// light ray (`C → 0`): a slope of more than the whole depth range per
    /// texel, or nothing finite.
    #[must_use]
    pub fn slope<F: DepthFormat>(&self, raster: &RasterConfig) -> Option<Slope> {
        let [a, b, c, _] = self.0;
        let range = (F::SCALE as f64) * 4_294_967_296.0;
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
    // "All nearby samples": the filter's own and the 2×2 texels around the
    // point, so that a lone sample (a point filter, or a jittered filter on
    // a footprint under a texel) is not taken as agreement with itself.
    let ordinary = lookup(map, cfg, l, None, probe);
    // Bilinear and boxes of 2 or more already read those texels.
    let covers_2x2 = matches!(cfg.filter, Filter::Bilinear) || matches!(cfg.filter, Filter::Box { size } if size >= 2);
    let around = || ShadowConfig { filter: Filter::Box { size: 2 }, ..*cfg };
    let agree = |s: Shadow| s == Shadow::ZERO || s == Shadow::ONE;
    if agree(ordinary) && (covers_2x2 || lookup(map, &around(), l, None, probe) == ordinary) {
        probe.event(Event::TrivialPixel { lit: ordinary == Shadow::ZERO });
        return ordinary;
    }
    probe.event(Event::TangentSetup);
    match setup() {
        Some(slope) => lookup(map, cfg, l, Some(slope), probe),
        None => {
            probe.event(Event::TangentFallback);
            ordinary
        }
    }
}
