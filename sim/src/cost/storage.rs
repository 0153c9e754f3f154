//! Depth-map storage schemes and what each costs in bytes: Reeves, Salesin
//! & Cook 1987, §5 and Table 2 ("Depth Map Storage").
//!
//! A finished map (one or two buffers, `z1` and `z2`, of `W × H` texels of
//! `b` bytes each; the clear value is the far plane, Reeves' "infinite
//! depth") can be kept as:
//!
//! | scheme | bytes |
//! |---|---|
//! | **raw** | `W·H·b·u` for `u` buffers |
//! | **bounding box** of the texels holding a finite (non-clear) depth in any buffer; texels outside it are not stored | `BOX_HEADER_BYTES` `+ w·h·b·u` for a `w × h` box (`w·h = 0` for an empty map) |
//! | **tiles** of `T × T` texels (Reeves' 32×32; partial at the right and bottom edges), storing only tiles with a finite depth in any buffer, each with its max depth per buffer (§3.3: "store a maximum z value with each tile") | `TILE_ENTRY_BYTES`` · n + Σ (a·b + b)·u` over the stored tiles, `n` tiles in the grid, `a` a stored tile's texels |
//!
//! The tile scheme's directory has one entry per tile of the grid: where the
//! tile's texels are, or that it is absent (every texel clear). Texel sizes
//! `b` are the formats' stored widths ([`DepthFormatKind::bytes`]: 2, 3 and
//! 4 bytes; 24-bit texels pack into 3).
//!
//! [`SparseTiles`] is the tile scheme as a store: it answers texel reads
//! exactly as the dense buffer does (an absent tile reads as clear), and
//! [`SparseTiles::bytes`] is the tile scheme's count for its one buffer.
//! [`storage_bytes`] counts all three schemes for a map's buffers (a light
//! pass's: `RawMaps::buffers`).
//!
//! ```
//! use umbra_sim::cost::storage::{MapShape, REEVES_TILE, storage_bytes};
//! // A 64 × 64 map of 16-bit texels, clear but for one texel.
//! let shape = MapShape { width: 64, height: 64, texel_bytes: 2, clear: 0xffff };
//! let mut z = vec![0xffff; 64 * 64];
//! z[0] = 100;
//! let b = storage_bytes(&shape, &[&z], REEVES_TILE)?;
//! // Raw: 64·64·2. Box: 8 + 1·1·2. Tiles: 4 entries of 4 B, then one
//! // stored 32 × 32 tile of 2-byte texels and its 2-byte max depth.
//! assert_eq!((b.raw, b.bounding_box, b.tiles), (8192, 10, 16 + 2048 + 2));
//! assert_eq!((b.grid_tiles, b.stored_tiles), (4, 1));
//! # Ok::<(), umbra_sim::cost::storage::StorageError>(())
//! ```

use umbra_core::DepthFormatKind;

/// Bytes of the bounding-box scheme's header: the box as four `u16`
/// (first column, first row, width, height; map sides are at most 2¹⁴).
pub const BOX_HEADER_BYTES: u64 = 8;

/// Bytes of one entry of the tile scheme's directory (a `u32` offset, or a
/// marker for an absent tile).
pub const TILE_ENTRY_BYTES: u64 = 4;

/// Reeves et al.'s tile side (1987, Table 2): the planner stores its maps
/// in tiles of this side.
pub const REEVES_TILE: u32 = 32;

/// Largest map side (the core's limit).
const MAX_SIDE: u32 = 1 << umbra_core::budget::MAX_TARGET_BITS;

/// A map's shape as far as storage goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MapShape {
    /// Width, texels.
    pub width: u32,
    /// Height, texels.
    pub height: u32,
    /// Stored bytes per texel, `1..=4`.
    pub texel_bytes: u32,
    /// The clear (far) value, as raw bits: texels holding it are empty.
    pub clear: u32,
}

impl MapShape {
    /// The shape of a `width × height` map in `format`, cleared to its far value.
    #[must_use]
    pub fn of_format(width: u32, height: u32, format: DepthFormatKind) -> Self {
        Self { width, height, texel_bytes: format.bytes(), clear: crate::base::maps::raw_far(format) }
    }

    fn texels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    fn check(&self, tile: u32) -> Result<(), StorageError> {
        if self.width == 0 || self.height == 0 || self.width > MAX_SIDE || self.height > MAX_SIDE {
            return Err(StorageError::MapSize { width: self.width, height: self.height });
        }
        if !(1..=4).contains(&self.texel_bytes) {
            return Err(StorageError::TexelBytes { bytes: self.texel_bytes });
        }
        if tile == 0 || tile > MAX_SIDE {
            return Err(StorageError::TileSize { size: tile });
        }
        Ok(())
    }
}

/// A storage request the schemes cannot answer.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum StorageError {
    /// Width or height is zero or above 2¹⁴.
    #[error("map size {width}x{height} is outside 1..=16384 on each side")]
    MapSize {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
    },
    /// Bytes per texel outside `1..=4`.
    #[error("{bytes} bytes per texel is outside 1..=4")]
    TexelBytes {
        /// Bytes asked for.
        bytes: u32,
    },
    /// Tile side zero or above 2¹⁴.
    #[error("tile size {size} is outside 1..=16384")]
    TileSize {
        /// Side asked for.
        size: u32,
    },
    /// A buffer whose length is not `width × height`.
    #[error("buffer `{buffer}` has {found} texels, the map has {expected}")]
    BufferLength {
        /// Which buffer (`z1`, `z2`, or its position).
        buffer: String,
        /// `width × height`.
        expected: usize,
        /// Its length.
        found: usize,
    },
    /// A texel read outside the map.
    #[error("texel ({x}, {y}) is outside the {width}x{height} map")]
    OutOfMap {
        /// Column read.
        x: u32,
        /// Row read.
        y: u32,
        /// Map width.
        width: u32,
        /// Map height.
        height: u32,
    },
}

/// A half-open rectangle of texels `[x0, x1) × [y0, y1)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexelBox {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl TexelBox {
    /// Width, texels.
    #[must_use]
    pub(crate) const fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    /// Texels inside.
    #[must_use]
    pub(crate) fn area(&self) -> u64 {
        u64::from(self.x1 - self.x0) * u64::from(self.y1 - self.y0)
    }
}

/// The bytes of each scheme for one map (all its buffers), with what they
/// were computed from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct StorageBytes {
    /// The raw scheme.
    pub raw: u64,
    /// The bounding-box scheme, header included.
    pub bounding_box: u64,
    /// The tile scheme, directory and per-tile max depths included.
    pub tiles: u64,
    /// Buffers counted (1, or 2 for a dual map).
    pub buffers: u32,
    /// Texels inside the bounding box of finite depths.
    pub box_texels: u64,
    /// Tiles in the grid.
    pub grid_tiles: u64,
    /// Tiles stored (holding a finite depth).
    pub stored_tiles: u64,
}

impl StorageBytes {
    /// This map's bytes and `other`'s, kept side by side (a cascade's
    /// maps): each scheme's bytes, texels and tiles added; the buffers a
    /// map, as each keeps them.
    #[must_use]
    pub const fn plus(&self, other: &Self) -> Self {
        Self {
            raw: self.raw + other.raw,
            bounding_box: self.bounding_box + other.bounding_box,
            tiles: self.tiles + other.tiles,
            buffers: self.buffers,
            box_texels: self.box_texels + other.box_texels,
            grid_tiles: self.grid_tiles + other.grid_tiles,
            stored_tiles: self.stored_tiles + other.stored_tiles,
        }
    }
}

/// The tile grid of a map: tiles across and down.
fn grid(shape: &MapShape, tile: u32) -> (u32, u32) {
    (shape.width.div_ceil(tile), shape.height.div_ceil(tile))
}

/// The texels of tile `(tx, ty)`, clipped to the map.
fn tile_box(shape: &MapShape, tile: u32, tx: u32, ty: u32) -> TexelBox {
    let (x0, y0) = (tx * tile, ty * tile);
    TexelBox { x0, y0, x1: (x0 + tile).min(shape.width), y1: (y0 + tile).min(shape.height) }
}

/// Check that every buffer has `width × height` texels.
fn check_buffers(shape: &MapShape, tile: u32, buffers: &[&[u32]]) -> Result<(), StorageError> {
    shape.check(tile)?;
    let expected = shape.texels();
    for (i, b) in buffers.iter().enumerate() {
        if b.len() != expected {
            let buffer = match i {
                0 => "z1".to_owned(),
                1 => "z2".to_owned(),
                _ => format!("buffer {i}"),
            };
            return Err(StorageError::BufferLength { buffer, expected, found: b.len() });
        }
    }
    Ok(())
}

/// Whether texel `(x, y)` holds a finite depth in any buffer.
fn finite(shape: &MapShape, buffers: &[&[u32]], x: u32, y: u32) -> bool {
    let i = y as usize * shape.width as usize + x as usize;
    buffers.iter().any(|b| b.get(i).is_some_and(|&t| t != shape.clear))
}

/// The bounding box of the texels holding a finite depth in any buffer
/// (Reeves et al. 1987 §5), or `None` when every texel is clear.
///
/// # Errors
/// [`StorageError`] for a bad shape or a buffer of the wrong length.
pub fn finite_box(shape: &MapShape, buffers: &[&[u32]]) -> Result<Option<TexelBox>, StorageError> {
    check_buffers(shape, 1, buffers)?;
    let mut b: Option<TexelBox> = None;
    for y in 0..shape.height {
        for x in 0..shape.width {
            if finite(shape, buffers, x, y) {
                let r = b.get_or_insert(TexelBox { x0: x, y0: y, x1: x + 1, y1: y + 1 });
                r.x0 = r.x0.min(x);
                r.x1 = r.x1.max(x + 1);
                r.y1 = y + 1;
            }
        }
    }
    Ok(b)
}

/// The bytes of the raw, bounding-box and tile schemes (tiles of side
/// `tile`) for a map of one or more buffers of raw texels, row-major.
///
/// # Errors
/// [`StorageError`] for a bad shape or tile size, or a buffer of the wrong length.
pub fn storage_bytes(shape: &MapShape, buffers: &[&[u32]], tile: u32) -> Result<StorageBytes, StorageError> {
    check_buffers(shape, tile, buffers)?;
    let b = u64::from(shape.texel_bytes);
    let u = buffers.len() as u64;
    let box_texels = finite_box(shape, buffers)?.map_or(0, |r| r.area());
    let (across, down) = grid(shape, tile);
    let mut stored_tiles = 0;
    let mut tile_data = 0;
    for ty in 0..down {
        for tx in 0..across {
            let r = tile_box(shape, tile, tx, ty);
            let occupied = (r.y0..r.y1).any(|y| (r.x0..r.x1).any(|x| finite(shape, buffers, x, y)));
            if occupied {
                stored_tiles += 1;
                tile_data += (r.area() * b + b) * u;
            }
        }
    }
    let grid_tiles = u64::from(across) * u64::from(down);
    #[allow(clippy::cast_possible_truncation, reason = "a handful of buffers")]
    let buffers_n = buffers.len() as u32;
    Ok(StorageBytes {
        raw: shape.texels() as u64 * b * u,
        bounding_box: BOX_HEADER_BYTES + box_texels * b * u,
        tiles: TILE_ENTRY_BYTES * grid_tiles + tile_data,
        buffers: buffers_n,
        box_texels,
        grid_tiles,
        stored_tiles,
    })
}

/// One buffer of a map kept as Reeves' tile scheme: only the tiles that
/// hold a finite depth, each with its max depth, behind a directory with
/// one entry per tile of the grid. Reads give exactly the dense buffer's
/// texels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SparseTiles {
    shape: MapShape,
    tile: u32,
    across: u32,
    /// Per tile of the grid, row-major: the index of its stored tile.
    directory: Vec<Option<u32>>,
    /// Offset of each stored tile's texels in `texels`.
    offsets: Vec<usize>,
    /// Max depth of each stored tile.
    max: Vec<u32>,
    /// The stored tiles' texels, each tile row-major at its clipped width.
    texels: Vec<u32>,
}

impl SparseTiles {
    /// Keep `dense` (row-major raw texels of `shape`) as tiles of side `tile`.
    ///
    /// # Errors
    /// [`StorageError`] for a bad shape or tile size, or a buffer of the wrong length.
    pub fn new(shape: MapShape, dense: &[u32], tile: u32) -> Result<Self, StorageError> {
        check_buffers(&shape, tile, &[dense])?;
        let (across, down) = grid(&shape, tile);
        let mut s = Self {
            shape,
            tile,
            across,
            directory: Vec::with_capacity(across as usize * down as usize),
            offsets: Vec::new(),
            max: Vec::new(),
            texels: Vec::new(),
        };
        let w = shape.width as usize;
        for ty in 0..down {
            for tx in 0..across {
                let r = tile_box(&shape, tile, tx, ty);
                let rows = (r.y0..r.y1).map(|y| &dense[y as usize * w + r.x0 as usize..y as usize * w + r.x1 as usize]);
                if rows.clone().flatten().all(|&t| t == shape.clear) {
                    s.directory.push(None);
                    continue;
                }
                let index = u32::try_from(s.offsets.len()).unwrap_or(u32::MAX);
                s.directory.push(Some(index));
                s.offsets.push(s.texels.len());
                let start = s.texels.len();
                rows.for_each(|row| s.texels.extend_from_slice(row));
                s.max.push(s.texels[start..].iter().copied().max().unwrap_or(shape.clear));
            }
        }
        Ok(s)
    }

    /// Texel `(x, y)`: the stored value, or the clear value in an absent tile.
    ///
    /// # Errors
    /// [`StorageError::OutOfMap`] outside the map.
    pub fn get(&self, x: u32, y: u32) -> Result<u32, StorageError> {
        let (width, height) = (self.shape.width, self.shape.height);
        if x >= width || y >= height {
            return Err(StorageError::OutOfMap { x, y, width, height });
        }
        let (tx, ty) = (x / self.tile, y / self.tile);
        let entry = self.directory.get(ty as usize * self.across as usize + tx as usize).copied().flatten();
        let Some(index) = entry else { return Ok(self.shape.clear) };
        let r = tile_box(&self.shape, self.tile, tx, ty);
        let at = self.offsets.get(index as usize).map(|o| o + ((y - r.y0) * r.width() + (x - r.x0)) as usize);
        Ok(at.and_then(|i| self.texels.get(i)).copied().unwrap_or(self.shape.clear))
    }

    /// The max depth of tile `(tx, ty)` over all its texels (clear ones
    /// included), `None` for an absent tile (every texel clear) or one
    /// outside the grid: a lookup whose every sample lies beyond it is in
    /// shadow without reading the tile (Reeves et al. 1987 §3.3).
    #[must_use]
    pub fn tile_max(&self, tx: u32, ty: u32) -> Option<u32> {
        if tx >= self.across {
            return None;
        }
        let index = self.directory.get(ty as usize * self.across as usize + tx as usize).copied().flatten()?;
        self.max.get(index as usize).copied()
    }

    /// Bytes of this buffer in the tile scheme: the directory, and each
    /// stored tile's texels and max depth ([`storage_bytes`]'s `tiles` for
    /// this buffer alone).
    #[must_use]
    pub fn bytes(&self) -> u64 {
        let b = u64::from(self.shape.texel_bytes);
        TILE_ENTRY_BYTES * self.directory.len() as u64 + (self.texels.len() as u64 + self.max.len() as u64) * b
    }
}
