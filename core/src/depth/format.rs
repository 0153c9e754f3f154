//! Depth formats: what a texel of the map stores, and how the rasterizer's
//! fixed-point depth becomes one.
//!
//! Depth follows the D3D / Vulkan convention: light clip space maps `z/w` to
//! `[0, 1]` (near = 0, far = 1), and an `n`-bit unsigned format stores
//! `round(z · (2ⁿ − 1))`, so `0` is the near plane and `2ⁿ − 1` the far plane
//! (the clear value). The f32 reference format stores the IEEE bits of `z`
//! itself; for non-negative floats those bits order exactly as the values do,
//! so every format compares texels as unsigned integers.
//!
//! # The interpolator's fixed point
//! Vertex depths enter the rasterizer as [`PlaneZ`]: an `I32F32` number of
//! *format LSBs* (for the f32 reference format, of `2⁻²⁴`), so 32 fraction
//! bits below the stored precision. The depth plane is stepped in that type
//! and every fragment is rounded once, to nearest, half up.
//!
//! # Out-of-range and non-finite depths
//! Quantisation is monotonic and saturating: depths below the near plane
//! (`z < 0`, including `−∞`) store `0`, depths beyond the far plane (`z > 1`,
//! including `+∞`) store the far value, and NaN stores the far value (it can
//! occlude nothing). The light pass clips against near and far before any of
//! this, so a rasterized fragment never needs to saturate by more than the
//! rounding of its vertices.

use fixed::types::I32F32;

use crate::budget::{DEPTH_ONE, PLANE_FRACTION_BITS, PLANE_ONE, ROUND_HALF};

/// Depth in the interpolator: format LSBs with 32 fraction bits.
pub type PlaneZ = I32F32;

/// A stored depth value: compared as an unsigned integer, whatever the format.
pub trait Texel: Copy + Ord + Default + core::fmt::Debug + Send + Sync + 'static {
    /// The texel as a value the hardware's comparators order as texels are
    /// ordered (the depth unit and the tile reductions compare these).
    type Key: Copy + Ord;
    /// The raw bits widened to `u32` (for checksums, images and `.npy` output).
    fn to_raw(self) -> u32;
    /// The comparators' value.
    fn key(self) -> Self::Key;
    /// The texel of a comparators' value.
    fn from_key(key: Self::Key) -> Self;
}

impl Texel for u16 {
    type Key = Self;
    #[inline]
    fn to_raw(self) -> u32 {
        u32::from(self)
    }
    #[inline(always)]
    fn key(self) -> Self {
        self
    }
    #[inline(always)]
    fn from_key(key: Self) -> Self {
        key
    }
}

/// Every 32-bit format's texels lie below 2³¹ (24-bit depth; the bits of
/// an f32 in `[0, 1]`), so signed comparators order them: a SIMD unit
/// without unsigned 32-bit compares (SSE2) needs no sign flips.
impl Texel for u32 {
    type Key = i32;
    #[inline]
    fn to_raw(self) -> u32 {
        self
    }
    #[inline(always)]
    fn key(self) -> i32 {
        self.cast_signed()
    }
    #[inline(always)]
    fn from_key(key: i32) -> Self {
        key.cast_unsigned()
    }
}

/// A depth format of the map. Implemented by the zero-sized [`D16`], [`D24`]
/// and [`F32`]; the light pass is generic over it, so each format compiles to
/// its own loops.
pub trait DepthFormat: Copy + Default + core::fmt::Debug + Send + Sync + 'static {
    /// What one texel holds in the caller's buffer.
    type Texel: Texel;
    /// The runtime name of this format.
    const KIND: DepthFormatKind;
    /// Depth `1.0` (the far plane) in [`PlaneZ`] integer units.
    const SCALE: i64;
    /// The far plane as a texel: the clear value.
    const FAR: Self::Texel;

    /// Round an interpolated depth to a texel, saturating at `0` and
    /// [`Self::FAR`]. This is the per-fragment path: integer only, except for
    /// the f32 reference format, whose whole point is the float.
    fn texel(z: PlaneZ) -> Self::Texel;

    /// The texel of a depth known to lie inside `[0, 1]` up to the
    /// interpolator's rounding error (a pixel centre inside the triangle),
    /// given as [`PlaneZ`] bits **plus [`ROUND_HALF`]**: then rounding is a
    /// shift and no clamp is needed (see [`crate::front::setup`] for the bound).
    /// Any other input gives an unspecified texel, never a panic.
    #[inline(always)]
    fn texel_inside(biased_bits: i64) -> Self::Texel {
        Self::texel(PlaneZ::from_bits(biased_bits.wrapping_sub(ROUND_HALF)))
    }

    /// Convert a depth in `[0, 1]` to the interpolator's fixed point,
    /// saturating and monotonic (see the module documentation for what
    /// happens outside `[0, 1]` and to NaN).
    #[inline]
    fn plane_z(z: f64) -> PlaneZ {
        let top = Self::SCALE << PLANE_FRACTION_BITS;
        if z.is_nan() || z >= 1.0 {
            return PlaneZ::from_bits(top);
        }
        if z <= 0.0 {
            return PlaneZ::ZERO;
        }
        // z · SCALE · 2³² < 2⁵⁷: exact in i64 after rounding.
        let bits = crate::round::round_ties_even(z * (Self::SCALE as f64) * PLANE_ONE);
        PlaneZ::from_bits(bits.clamp(0, top))
    }

    /// Quantise a depth `z` (light clip space `z/w`) to a texel.
    #[inline]
    fn quantize(z: f32) -> Self::Texel {
        Self::texel(Self::plane_z(f64::from(z)))
    }

    /// A texel widened to [`PlaneZ`] bits, exactly (for comparisons with
    /// the interpolator's depth).
    fn widen(t: Self::Texel) -> i64;

    /// The depth a texel stands for, in `[0, 1]` (for previews and reports).
    fn unquantize(t: Self::Texel) -> f64;
}

/// Round half up to whole LSBs, clamped to `[0, max]`, without overflow for
/// any input.
#[inline(always)]
fn round_lsb(z: PlaneZ, max: i64) -> i64 {
    let bits = z.to_bits();
    let lsb = (bits >> PLANE_FRACTION_BITS) + ((bits >> (PLANE_FRACTION_BITS - 1)) & 1);
    lsb.clamp(0, max)
}

/// 16-bit unsigned fixed-point depth.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct D16;

/// 24-bit unsigned fixed-point depth (held in a `u32`, moved as 3 bytes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct D24;

/// The f32 reference format: the IEEE bits of the depth.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct F32;

/// The n-bit unsigned formats: `round(z · (2ⁿ − 1))` in a `$texel`.
macro_rules! unorm_format {
    ($format:ident, $texel:ty, $bits:literal) => {
        impl DepthFormat for $format {
            type Texel = $texel;
            const KIND: DepthFormatKind = DepthFormatKind::$format;
            const SCALE: i64 = (1 << $bits) - 1;
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "2^bits - 1 fits the texel")]
            const FAR: $texel = Self::SCALE as $texel;

            #[inline(always)]
            fn texel(z: PlaneZ) -> $texel {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "clamped to [0, SCALE]")]
                let t = round_lsb(z, Self::SCALE) as $texel;
                t
            }

            /// The interpolator's integer part on the format's `n` wires:
            /// inside the triangle it lies in `[0, SCALE]` already, and any
            /// other input still gives a texel of `n` bits.
            #[inline(always)]
            fn texel_inside(biased_bits: i64) -> $texel {
                #[allow(
                    clippy::cast_possible_truncation,
                    clippy::cast_sign_loss,
                    reason = "masked to the format's bits"
                )]
                let t = ((biased_bits >> PLANE_FRACTION_BITS) & Self::SCALE) as $texel;
                t
            }

            #[inline(always)]
            fn widen(t: $texel) -> i64 {
                i64::from(t) << PLANE_FRACTION_BITS
            }

            fn unquantize(t: $texel) -> f64 {
                f64::from(t) / (Self::SCALE as f64)
            }
        }
    };
}

unorm_format!(D16, u16, 16);
unorm_format!(D24, u32, 24);

/// One [`PlaneZ`] bit of the f32 reference format, as a depth (exact).
#[allow(clippy::cast_possible_truncation, reason = "a power of two, exact in f32")]
const F32_UNIT: f32 = (1.0 / DEPTH_ONE) as f32;

impl DepthFormat for F32 {
    type Texel = u32;
    const KIND: DepthFormatKind = DepthFormatKind::F32;
    const SCALE: i64 = 1 << 24;
    const FAR: u32 = 0x3f80_0000; // 1.0f32

    #[inline(always)]
    fn texel(z: PlaneZ) -> u32 {
        let bits = z.to_bits().clamp(0, Self::SCALE << PLANE_FRACTION_BITS);
        // i64 → f32 rounds to nearest (monotonic); the scale is a power of two (exact).
        #[allow(clippy::cast_precision_loss, reason = "the f32 format's precision is the point")]
        let value = bits as f32 * F32_UNIT;
        value.to_bits()
    }

    #[inline]
    fn widen(t: u32) -> i64 {
        // The float times 2^DEPTH_BITS (exact in f64), rounded: the inverse of `texel`.
        crate::round::round_ties_even(f64::from(f32::from_bits(t)) * DEPTH_ONE)
    }

    fn unquantize(t: u32) -> f64 {
        f64::from(f32::from_bits(t))
    }
}

/// A depth format chosen at run time (the formats themselves are types).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthFormatKind {
    /// [`D16`].
    D16,
    /// [`D24`].
    D24,
    /// [`F32`].
    F32,
}

impl DepthFormatKind {
    /// Bits a texel of this format holds.
    #[must_use]
    pub const fn bits(self) -> u32 {
        match self {
            Self::D16 => 16,
            Self::D24 => 24,
            Self::F32 => 32,
        }
    }

    /// Bytes one texel of this format moves across a memory interface.
    #[must_use]
    pub const fn bytes(self) -> u32 {
        self.bits() / 8
    }
}

crate::spelled!(DepthFormatKind, "depth format", { D16 => "d16", D24 => "d24", F32 => "f32" });

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d3d_rounding_of_exact_values() {
        assert_eq!(D16::quantize(0.0), 0);
        assert_eq!(D16::quantize(1.0), 65535);
        assert_eq!(D16::quantize(0.5), 32768); // 32767.5 rounds half up
        assert_eq!(D24::quantize(0.25), 4_194_304); // round(0.25 · 16777215) = 4194303.75 → 4194304
        assert_eq!(F32::quantize(0.375), 0.375f32.to_bits());
    }

    #[test]
    fn saturation_and_nan() {
        assert_eq!(D16::quantize(-1.0), 0);
        assert_eq!(D16::quantize(f32::NEG_INFINITY), 0);
        assert_eq!(D16::quantize(7.0), D16::FAR);
        assert_eq!(D24::quantize(f32::INFINITY), D24::FAR);
        assert_eq!(D24::quantize(f32::NAN), D24::FAR);
        assert_eq!(F32::quantize(f32::NAN), F32::FAR);
        assert_eq!(D16::texel(PlaneZ::from_bits(i64::MAX)), D16::FAR);
        assert_eq!(D16::texel(PlaneZ::from_bits(i64::MIN)), 0);
    }
}
