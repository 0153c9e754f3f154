//! The silhouette map: one point per texel of the depth map's dual grid.

use crate::budget::{CORNER_SLACK_BITS, MAP_FRACTION_BITS};
use crate::config::ConfigError;

/// How far outside its texel a diagonal intersection still counts (Sen's
/// enlarged clip square): 2⁻⁸ texel, in 2⁻¹⁶ texels. A segment through a
/// corner then stores a point in all four texels around it.
pub const CORNER_SLACK: i64 = 1 << (MAP_FRACTION_BITS - CORNER_SLACK_BITS);

/// A silhouette point: its offset from the texel's top-left corner, in
/// 2⁻¹⁶ texels per axis (`0x8000` is the centre).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SilPoint {
    /// Offset to the right.
    pub x: u16,
    /// Offset down.
    pub y: u16,
}

impl SilPoint {
    /// The texel's centre: what an empty texel means.
    pub const CENTRE: Self = Self { x: 0x8000, y: 0x8000 };
}

/// How a silhouette map stores its points.
pub trait SilStore: Copy + Default + core::fmt::Debug + 'static {
    /// Bytes per texel.
    const BYTES: u32;
    /// Store a point.
    fn encode(p: SilPoint) -> Self;
    /// The stored point.
    fn decode(self) -> SilPoint;
}

impl Default for SilPoint {
    fn default() -> Self {
        Self::CENTRE
    }
}

/// Full precision: 16 bits per axis, 4 bytes per texel.
impl SilStore for SilPoint {
    const BYTES: u32 = 4;
    fn encode(p: SilPoint) -> Self {
        p
    }
    fn decode(self) -> SilPoint {
        self
    }
}

/// Sen's packed form: 4 bits per axis, one byte per texel. A nibble `q`
/// means `q/16` texel, so the centre (8, 8) is exact and the largest error
/// of a stored point is 1/32 texel per axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Packed(pub u8);

impl Default for Packed {
    fn default() -> Self {
        Self::encode(SilPoint::CENTRE)
    }
}

impl SilStore for Packed {
    const BYTES: u32 = 1;
    fn encode(p: SilPoint) -> Self {
        let q = |v: u16| ((u32::from(v) + 0x800) >> 12).min(15);
        #[allow(clippy::cast_possible_truncation, reason = "two nibbles")]
        let byte = (q(p.x) << 4 | q(p.y)) as u8;
        Self(byte)
    }
    fn decode(self) -> SilPoint {
        SilPoint { x: u16::from(self.0 >> 4) << 12, y: u16::from(self.0 & 15) << 12 }
    }
}

/// The dual grid of a `map_width × map_height` depth map:
/// `(map_width + 1) × (map_height + 1)` texels.
pub(super) fn dual(map_width: u32, map_height: u32, len: usize) -> Result<(u32, u32), ConfigError> {
    let (width, height) = (map_width.saturating_add(1), map_height.saturating_add(1));
    let expected = width as usize * height as usize;
    if len != expected {
        return Err(ConfigError::BufferLength { buffer: "silhouette", expected, found: len });
    }
    Ok((width, height))
}

/// The index of texel `(i, j)` of a `width × height` grid, if inside.
pub(super) fn index(width: u32, height: u32, i: i64, j: i64) -> Option<usize> {
    let (i, j) = (u32::try_from(i).ok()?, u32::try_from(j).ok()?);
    (i < width && j < height).then(|| j as usize * width as usize + i as usize)
}

/// A finished silhouette map, as the camera pass reads it.
#[derive(Clone, Copy, Debug)]
pub struct SilhouetteMap<'a, S: SilStore> {
    pub(super) width: u32,
    pub(super) height: u32,
    texels: &'a [S],
}

impl<'a, S: SilStore> SilhouetteMap<'a, S> {
    /// View the silhouette map of a `map_width × map_height` depth map.
    ///
    /// # Errors
    /// [`ConfigError::BufferLength`] unless `texels` has
    /// `(map_width + 1) × (map_height + 1)` entries.
    pub fn view(map_width: u32, map_height: u32, texels: &'a [S]) -> Result<Self, ConfigError> {
        let (width, height) = dual(map_width, map_height, texels.len())?;
        Ok(Self { width, height, texels })
    }

    /// Texels across.
    #[must_use]
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Texels down.
    #[must_use]
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// The stored point of texel `(i, j)`; the centre when empty or outside.
    #[must_use]
    pub fn point(&self, i: i64, j: i64) -> SilPoint {
        index(self.width, self.height, i, j).and_then(|k| self.texels.get(k)).map_or(SilPoint::CENTRE, |s| s.decode())
    }
}
