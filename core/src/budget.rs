//! The fixed-point budget: every bit width and bound of the core in one
//! place, each with its derivation and a compile-time check.
//!
//! Other modules take their shifts and scales from here; a number written
//! in a unit's documentation is one of these. The chain, front to back:
//!
//! | quantity | bound | where |
//! |---|---|---|
//! | target side | `2^MAX_TARGET_BITS` = 16 384 pixels | [`crate::config::RasterConfig::new`] |
//! | snapped coordinate | `±2^COORD_BITS` subpixels (±2¹⁶ pixels of guard band, 8 subpixel bits) | [`crate::front::snap`](mod@crate::front::snap) |
//! | in a window | `±2^WINDOW_COORD_BITS` subpixels | [`crate::front::setup`] |
//! | edge function at a pixel centre | `< 2^EDGE_BITS` = 2⁵³ (`i64`) | [`crate::front::setup::Edge`] |
//! | depth in the interpolator | `[0, 2^DEPTH_BITS)` = `[0, 2⁵⁶)` ([`crate::depth::PlaneZ`], 32 fraction bits below an LSB) | [`crate::depth`] |
//! | depth plane numerators | `< 2^DEPTH_NUMERATOR_BITS` (`i128`) | [`crate::front::setup::DepthPlane`] |
//! | map coordinate | texels with `MAP_FRACTION_BITS` = 16 fraction bits | [`crate::shadow::MapCoord`] |
//! | shading forms | denominator scaled by `2^DENOMINATOR_BITS` = 2⁴⁴, narrow below `2^NARROW_FORM_BITS` | [`crate::shade`] |

use core::ops::RangeInclusive;

use fixed::types::{I16F16, I32F32, U16F16};

// ---------------------------------------------------------------- target

/// Largest target side: `2^MAX_TARGET_BITS` pixels (16 384, a 16K map).
pub const MAX_TARGET_BITS: u32 = 14;

/// Smallest and largest tile side (tiles are square, sides a power of two).
pub const TILE_SIZES: RangeInclusive<u32> = 8..=128;

/// Largest number of subpixel bits the coordinate budget allows (D3D11 and
/// llvmpipe snap to 8).
pub const MAX_SUBPIXEL_BITS: u32 = 8;

// ---------------------------------------------------- snapped coordinates

/// Snapped coordinates lie within `±2^GUARD_BITS` pixels: the guard band.
pub const GUARD_BITS: u32 = 16;

/// Snapped coordinates lie within `±2^COORD_BITS` subpixels.
pub const COORD_BITS: u32 = GUARD_BITS + MAX_SUBPIXEL_BITS;

/// Relative to a window's origin (at most `2^MAX_TARGET_BITS` pixels in),
/// within `±2^WINDOW_COORD_BITS` subpixels: the setup's range.
pub const WINDOW_COORD_BITS: u32 = COORD_BITS + 1;

const _: () = assert!(
    GUARD_BITS > MAX_TARGET_BITS,
    "the guard band must contain the target, and a window's shift stay inside it"
);

// -------------------------------------------------------- edge functions

/// Edge functions at a pixel centre of the target lie below `2^EDGE_BITS`:
/// a coordinate difference (below `2^(WINDOW_COORD_BITS + 1)`) times
/// another, two such products summed.
pub const EDGE_BITS: u32 = 2 * (WINDOW_COORD_BITS + 1) + 1;

const _: () = assert!(EDGE_BITS < 63, "edge functions must fit in i64");

// ------------------------------------------------------------------ depth

/// Fraction bits of [`crate::depth::PlaneZ`] below one stored LSB.
pub const PLANE_FRACTION_BITS: u32 = 32;

/// One LSB in [`crate::depth::PlaneZ`] bits, as an f64 (exact).
#[allow(clippy::cast_precision_loss, reason = "a power of two")]
pub const PLANE_ONE: f64 = (1u64 << PLANE_FRACTION_BITS) as f64;

/// Half an LSB in [`crate::depth::PlaneZ`] bits: added once so that
/// rounding is a shift.
pub const ROUND_HALF: i64 = 1 << (PLANE_FRACTION_BITS - 1);

/// Bits of the widest format's stored range: 24-bit depth, and the f32
/// format's `[0, 1]` at the same scale.
pub const MAX_FORMAT_BITS: u32 = 24;

/// A depth in `[0, 1]` is below `2^DEPTH_BITS` in [`crate::depth::PlaneZ`]
/// bits: `2^MAX_FORMAT_BITS` LSBs of `2^PLANE_FRACTION_BITS`.
pub const DEPTH_BITS: u32 = MAX_FORMAT_BITS + PLANE_FRACTION_BITS;

/// One [`crate::depth::PlaneZ`] bit of the widest format's range, as a
/// depth in `[0, 1]` (`2^-DEPTH_BITS`); its inverse as an f64 (exact).
#[allow(clippy::cast_precision_loss, reason = "a power of two")]
pub const DEPTH_ONE: f64 = (1u64 << DEPTH_BITS) as f64;

/// How far beyond the far plane [`crate::front::snap::snap_beyond_far`]
/// keeps depths, in multiples of it: a perspective camera's depth never
/// exceeds `f/(f − n)`.
pub const BEYOND_FAR: i64 = 16;

const _: () = assert!(
    (1i64 << DEPTH_BITS).checked_mul(BEYOND_FAR).is_some(),
    "a depth beyond the far plane must stay inside the plane's i64"
);

/// Depth differences between a triangle's vertices (at most [`BEYOND_FAR`]
/// far planes apart, each below `2^DEPTH_BITS`, and a sign) lie below
/// `2^DEPTH_DIFFERENCE_BITS`.
pub const DEPTH_DIFFERENCE_BITS: u32 = DEPTH_BITS + BEYOND_FAR.ilog2() + 1;

/// The depth plane's numerators `Δz·Δy` lie below `2^DEPTH_NUMERATOR_BITS`;
/// a per-pixel step (a numerator shifted by the subpixel bits) times a
/// coordinate difference stays below `2^127`.
pub const DEPTH_NUMERATOR_BITS: u32 = DEPTH_DIFFERENCE_BITS + WINDOW_COORD_BITS + 1;

const _: () = assert!(
    DEPTH_NUMERATOR_BITS + 1 + MAX_SUBPIXEL_BITS + WINDOW_COORD_BITS + 1 < 127,
    "the depth plane must fit in i128"
);

/// Setup solves the plane's steps in f64 when their sum over the triangle
/// stays below `2^SLOPE_F64_BITS`: with the quotient's relative error below
/// 2⁻⁵¹, no fragment moves by more than `2^(SLOPE_F64_BITS − 51)` = 2⁵
/// units (2⁻²⁷ LSB) beyond the exact path's own rounding.
pub const SLOPE_F64_BITS: u32 = 56;

/// `2^SLOPE_F64_BITS` as an f64 (exact).
#[allow(clippy::cast_precision_loss, reason = "a power of two")]
pub const SLOPE_F64_LIMIT: f64 = (1u64 << SLOPE_F64_BITS) as f64;

const _: () = assert!(SLOPE_F64_BITS - 51 <= PLANE_FRACTION_BITS - 27, "f64 slopes stay within 2^-27 LSB");

// -------------------------------------------------------- map coordinates

/// Fraction bits of a map coordinate ([`crate::shadow::MapCoord`]), of a
/// silhouette point, of the bilinear filter's weights and of the shadow
/// fraction ([`crate::shadow::Shadow`]).
pub const MAP_FRACTION_BITS: u32 = 16;

/// One texel in map-coordinate bits.
pub const MAP_ONE: i64 = 1 << MAP_FRACTION_BITS;

/// Half a texel in map-coordinate bits (a texel's centre).
pub const MAP_HALF: i64 = MAP_ONE / 2;

/// One texel as an f64 (exact): a coordinate's scale.
#[allow(clippy::cast_precision_loss, reason = "a power of two")]
pub const MAP_SCALE: f64 = MAP_ONE as f64;

const _: () = assert!(I16F16::FRAC_NBITS == MAP_FRACTION_BITS, "map coordinates have MAP_FRACTION_BITS");
const _: () = assert!(U16F16::FRAC_NBITS == MAP_FRACTION_BITS, "shadow fractions have MAP_FRACTION_BITS");
const _: () = assert!(I32F32::FRAC_NBITS == PLANE_FRACTION_BITS, "PlaneZ has PLANE_FRACTION_BITS");
const _: () = assert!(
    2 * MAP_FRACTION_BITS == PLANE_FRACTION_BITS,
    "bilinear weights' products sum to one LSB of PlaneZ: texels widen by the same shift"
);

/// The silhouette pass gives a fragment to every texel within
/// `2^-CORNER_SLACK_BITS` texel of a segment.
pub const CORNER_SLACK_BITS: u32 = 8;

// ------------------------------------------------------------ shading unit

/// The denominator `Λw` of the shading unit's forms is scaled by
/// `2^DENOMINATOR_BITS` over the target, so that the numerators (up to
/// `W/2` times larger) and their products with pixel coordinates stay well
/// inside `i128`, and the rounding of each coefficient moves `u` by under
/// 2⁻²⁰ texel.
pub const DENOMINATOR_BITS: u32 = 44;

/// `2^DENOMINATOR_BITS` as an f64 (exact).
#[allow(clippy::cast_precision_loss, reason = "a power of two")]
pub const DENOMINATOR_SCALE: f64 = (1u64 << DENOMINATOR_BITS) as f64;

const _: () = assert!(
    DENOMINATOR_BITS + MAX_TARGET_BITS + MAX_TARGET_BITS + MAP_FRACTION_BITS + 1 < 127,
    "a form's products with pixel coordinates, shifted to map bits, fit i128"
);

/// A triangle whose forms stay below `2^NARROW_FORM_BITS` over the whole
/// target is evaluated in `i64` arithmetic per pixel.
pub const NARROW_FORM_BITS: u32 = 60;

const _: () = assert!(NARROW_FORM_BITS < 63, "narrow forms fit i64");

/// The divider's estimate path serves divisors below `2^DIVIDER_BITS`, so
/// that remainders of a few divisors fit `i64`.
pub const DIVIDER_BITS: u32 = 61;

// ---------------------------------------------------------- the vertex unit

/// Bits of an f64's fraction: adding and removing `2^F64_FRACTION_BITS`
/// rounds to an integer.
pub const F64_FRACTION_BITS: u32 = f64::MANTISSA_DIGITS - 1;

/// `2^F64_FRACTION_BITS` as an f64 (exact).
#[allow(clippy::cast_precision_loss, reason = "a power of two")]
pub const F64_ROUNDING: f64 = (1u64 << F64_FRACTION_BITS) as f64;
