//! The tile grid: square tiles of `2^tile_shift` pixels, in row-major order,
//! and half-open rectangles of pixels.

/// A tile's column and row in the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TileId {
    /// Tile column.
    pub x: u16,
    /// Tile row.
    pub y: u16,
}

/// A half-open rectangle of pixels `[x0, x1) × [y0, y1)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TileRect {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl TileRect {
    /// The intersection, or `None` when it is empty.
    #[inline]
    #[must_use]
    pub fn intersect(&self, other: &Self) -> Option<Self> {
        let r = Self {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        };
        (r.x0 < r.x1 && r.y0 < r.y1).then_some(r)
    }

    /// This rectangle `by` pixels further right and down (saturating).
    #[inline]
    #[must_use]
    pub const fn moved(&self, by: [u32; 2]) -> Self {
        Self {
            x0: self.x0.saturating_add(by[0]),
            y0: self.y0.saturating_add(by[1]),
            x1: self.x1.saturating_add(by[0]),
            y1: self.y1.saturating_add(by[1]),
        }
    }

    /// Width in pixels.
    #[must_use]
    pub const fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    /// Height in pixels.
    #[must_use]
    pub const fn height(&self) -> u32 {
        self.y1 - self.y0
    }

    /// Number of pixels.
    #[must_use]
    pub const fn area(&self) -> u32 {
        self.width() * self.height()
    }
}
