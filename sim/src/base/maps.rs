//! What the layers share about maps and images: a raw texel's depth, a
//! format's clear value, and the tiling a pass walks its target in.

use umbra_core::depth::Texel;
use umbra_core::{D16, D24, DepthFormat, DepthFormatKind, F32, RasterConfig};

/// Evaluate `$body` with `$F` the depth-format type that the run-time
/// [`DepthFormatKind`] `$kind` names: the one dispatch from a format chosen
/// at run time to the type the core is built for.
///
/// ```text
/// let bits = with_format!(kind, F => F::FAR_BITS);
/// ```
macro_rules! with_format {
    ($kind:expr, $F:ident => $body:expr) => {
        match $kind {
            umbra_core::DepthFormatKind::D16 => {
                type $F = umbra_core::D16;
                $body
            }
            umbra_core::DepthFormatKind::D24 => {
                type $F = umbra_core::D24;
                $body
            }
            umbra_core::DepthFormatKind::F32 => {
                type $F = umbra_core::F32;
                $body
            }
        }
    };
}
pub(crate) use with_format;

/// The depth a raw texel of `format` stands for, in `[0, 1]`.
#[must_use]
pub(crate) fn raw_depth(format: DepthFormatKind, raw: u32) -> f64 {
    match format {
        DepthFormatKind::D16 => D16::unquantize(u16::try_from(raw).unwrap_or(u16::MAX)),
        DepthFormatKind::D24 => D24::unquantize(raw),
        DepthFormatKind::F32 => F32::unquantize(raw),
    }
}

/// The clear (far) value of `format`, as raw bits.
#[must_use]
pub fn raw_far(format: DepthFormatKind) -> u32 {
    with_format!(format, F => F::FAR.to_raw())
}

/// How the visibility unit walks the image: the bits depend on neither; the
/// architecture a pass is costed on does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tiling {
    /// Side of the tiles.
    pub tile: u32,
    /// Finish each draw before the next (an immediate-mode machine).
    pub per_draw: bool,
}

impl Tiling {
    /// The default tiles, every draw binned before any is drawn.
    pub const DEFAULT: Self = Self { tile: RasterConfig::DEFAULT_TILE_SIZE, per_draw: false };
}
