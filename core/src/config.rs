//! Hardware parameters, validated once.
//!
//! Everything a designer chooses — target size, tile size, subpixel bits,
//! depth unit, max-z culling — is a parameter here. [`RasterConfig::new`]
//! checks it against the fixed-point budget in [`crate::budget`];
//! afterwards the hot path trusts it.

use core::fmt;

use crate::budget::{GUARD_BITS, MAX_SUBPIXEL_BITS, MAX_TARGET_BITS, TILE_SIZES};
use crate::grid::{TileId, TileRect};

/// The rasterizer's geometry: target, tiles and subpixel grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RasterConfig {
    width: u32,
    height: u32,
    tile_shift: u32,
    subpixel_bits: u32,
    /// The whole target the viewport transform maps NDC onto.
    view: [u32; 2],
    /// Where this target sits in it (a window of it; `[0, 0]` for all of it).
    origin: [u32; 2],
}

impl RasterConfig {
    /// The subpixel precision of D3D11-class hardware.
    pub const DEFAULT_SUBPIXEL_BITS: u32 = 8;
    /// A tile size that suits most targets.
    pub const DEFAULT_TILE_SIZE: u32 = 32;

    /// Validate a raster configuration.
    ///
    /// # Errors
    /// [`ConfigError::TargetSize`] unless `1 ≤ width, height ≤ 2^14`;
    /// [`ConfigError::TileSize`] unless the tile size is a power of two in
    /// `8..=128`; [`ConfigError::SubpixelBits`] unless `1 ≤ bits ≤ 8` (pixel
    /// centres sit half a pixel off the grid, so at least one bit is needed).
    pub fn new(width: u32, height: u32, tile_size: u32, subpixel_bits: u32) -> Result<Self, ConfigError> {
        let max = 1 << MAX_TARGET_BITS;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(ConfigError::TargetSize { width, height });
        }
        if !TILE_SIZES.contains(&tile_size) || !tile_size.is_power_of_two() {
            return Err(ConfigError::TileSize { size: tile_size });
        }
        if subpixel_bits == 0 || subpixel_bits > MAX_SUBPIXEL_BITS {
            return Err(ConfigError::SubpixelBits { bits: subpixel_bits });
        }
        Ok(Self {
            width,
            height,
            tile_shift: tile_size.trailing_zeros(),
            subpixel_bits,
            view: [width, height],
            origin: [0, 0],
        })
    }

    /// A window of this target: `width × height` pixels from `(x0, y0)`,
    /// on tile boundaries. The viewport transform stays the whole target's
    /// and snapped coordinates shift by the origin exactly, so a window
    /// rasterizes exactly the fragments the whole target has in it: the
    /// light pass can run on bands of tiles in parallel.
    ///
    /// # Errors
    /// [`ConfigError::Window`] unless the window lies inside the target
    /// and starts on a tile boundary.
    pub fn window(&self, x0: u32, y0: u32, width: u32, height: u32) -> Result<Self, ConfigError> {
        let t = self.tile_size();
        let fits = |o: u32, n: u32, all: u32| n > 0 && o.checked_add(n).is_some_and(|e| e <= all);
        if !fits(x0, width, self.width)
            || !fits(y0, height, self.height)
            || !x0.is_multiple_of(t)
            || !y0.is_multiple_of(t)
        {
            return Err(ConfigError::Window { x0, y0, width, height });
        }
        Ok(Self { width, height, origin: [self.origin[0] + x0, self.origin[1] + y0], ..*self })
    }

    /// The whole target's size, which the viewport transform maps onto.
    #[must_use]
    pub const fn view(&self) -> [u32; 2] {
        self.view
    }

    /// Where this target sits in the whole (`[0, 0]` unless a window).
    #[must_use]
    pub const fn origin(&self) -> [u32; 2] {
        self.origin
    }

    /// Target width in pixels (texels of the map).
    #[must_use]
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Target height in pixels.
    #[must_use]
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// Tile side in pixels.
    #[must_use]
    pub const fn tile_size(&self) -> u32 {
        1 << self.tile_shift
    }

    /// `log2` of the tile side.
    #[must_use]
    pub const fn tile_shift(&self) -> u32 {
        self.tile_shift
    }

    /// Fraction bits of the snapped vertex coordinates.
    #[must_use]
    pub const fn subpixel_bits(&self) -> u32 {
        self.subpixel_bits
    }

    /// Tiles across and down (partial tiles at the right and bottom count).
    #[must_use]
    pub const fn tiles(&self) -> (u32, u32) {
        let t = self.tile_size();
        (self.width.div_ceil(t), self.height.div_ceil(t))
    }

    /// Number of tiles.
    #[must_use]
    pub const fn tile_count(&self) -> usize {
        let (x, y) = self.tiles();
        x as usize * y as usize
    }

    /// Number of texels of the target.
    #[must_use]
    pub const fn texel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

/// Which depths the depth unit keeps per texel (Wang & Molnar 1994, §3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthUnit {
    /// The nearest depth `z1` only (Williams' map; with [`CullMode::Front`]
    /// the nearest light-averted surface: second depth by front-face culling).
    Single,
    /// Nearest `z1` and second nearest `z2`, both updated per fragment.
    Dual,
}

/// Which triangles the light pass discards by their facing. Facing is seen
/// from the light: counter-clockwise in normalised device coordinates
/// (y up) is front-facing, i.e. faces the light. The mode is chosen per draw
/// call, so culled solids and unculled open surfaces share one map
/// (Wang & Molnar 1994 §3.3–3.4; Weiskopf & Ertl 2003).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CullMode {
    /// Keep every triangle (open, two-sided surfaces).
    #[default]
    None,
    /// Discard light-averted triangles (solids; first depth).
    Back,
    /// Discard light-facing triangles (solids; second depth by front-face culling).
    Front,
}

crate::spelled!(CullMode, "cull mode", { None => "none", Back => "back", Front => "front" });

/// Everything the light pass needs to know besides its buffers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightPassConfig {
    /// Target, tiles and subpixel grid.
    pub raster: RasterConfig,
    /// Single or dual depth.
    pub unit: DepthUnit,
    /// Skip triangles and blocks that lie behind the tile's max stored depth.
    pub max_z_cull: bool,
}

/// A configuration or buffer the hardware cannot use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ConfigError {
    /// Width or height is zero or larger than `2^14`.
    TargetSize {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// The tile side is not a power of two in `8..=128`.
    TileSize {
        /// The side asked for.
        size: u32,
    },
    /// Subpixel bits outside `1..=8`.
    SubpixelBits {
        /// The bits asked for.
        bits: u32,
    },
    /// A window outside the target or off the tile grid.
    Window {
        /// First column.
        x0: u32,
        /// First row.
        y0: u32,
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
    },
    /// A caller-owned buffer has the wrong length.
    BufferLength {
        /// Which buffer.
        buffer: &'static str,
        /// The length the configuration needs.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// The light pass was not built with the datapath the configuration
    /// needs ([`crate::light_pass::Datapaths`]).
    NotBuilt {
        /// The depth unit asked for.
        unit: DepthUnit,
        /// Whether triangle ids were asked for.
        ids: bool,
        /// Whether max-z culling was asked for.
        max_z_cull: bool,
    },
    /// The shadow unit was not built with a datapath the configuration
    /// needs ([`crate::shadow::Built`]).
    ShadowNotBuilt {
        /// What is missing.
        missing: &'static str,
    },
    /// A cascade selector's registers: more than eight cascades, a band
    /// register per split missing, or splits and bands out of order.
    Cascades {
        /// Split registers given.
        splits: usize,
        /// Band registers given.
        bands: usize,
    },
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::TargetSize { width, height } => {
                write!(f, "target size {width}x{height} is outside 1..={} on each side", 1u32 << MAX_TARGET_BITS)
            }
            Self::TileSize { size } => write!(f, "tile size {size} is not a power of two in 8..=128"),
            Self::SubpixelBits { bits } => {
                write!(f, "subpixel bits {bits} is outside 1..={MAX_SUBPIXEL_BITS}")
            }
            Self::Window { x0, y0, width, height } => {
                write!(f, "window {width}x{height} at ({x0}, {y0}) is not inside the target on tile boundaries")
            }
            Self::BufferLength { buffer, expected, found } => {
                write!(f, "buffer `{buffer}` has length {found}, the configuration needs {expected}")
            }
            Self::NotBuilt { unit, ids, max_z_cull } => {
                let ids = if ids { " with triangle ids" } else { "" };
                let cull = if max_z_cull { "with" } else { "without" };
                write!(f, "this light pass is not built with the {unit:?} depth unit{ids} {cull} max-z culling")
            }
            Self::ShadowNotBuilt { missing } => write!(f, "this shadow unit is not built with {missing}"),
            Self::Cascades { splits, bands } => write!(
                f,
                "cascade selector: {splits} splits and {bands} bands, which must be as many, at most 7, increasing, each band at or below its split and above the previous split"
            ),
        }
    }
}

impl core::error::Error for ConfigError {}

impl DepthUnit {
    /// Depth buffers this unit keeps.
    #[must_use]
    pub const fn buffers(self) -> u32 {
        match self {
            Self::Single => 1,
            Self::Dual => 2,
        }
    }
}

/// The target's tiles and guard band.
impl RasterConfig {
    /// The tile at a flat (row-major) index.
    #[must_use]
    pub fn tile_id(&self, index: usize) -> TileId {
        let across = self.tiles().0 as usize;
        #[allow(clippy::cast_possible_truncation, reason = "at most 2^14 / 8 tiles per side")]
        TileId { x: (index % across) as u16, y: (index / across) as u16 }
    }

    /// The flat (row-major) index of a tile.
    #[must_use]
    pub fn tile_index(&self, tile: TileId) -> usize {
        usize::from(tile.y) * self.tiles().0 as usize + usize::from(tile.x)
    }

    /// The pixels of a tile, clipped to the target.
    #[must_use]
    pub fn tile_rect(&self, tile: TileId) -> TileRect {
        let s = self.tile_shift();
        let x0 = u32::from(tile.x) << s;
        let y0 = u32::from(tile.y) << s;
        TileRect {
            x0,
            y0,
            x1: (x0 + self.tile_size()).min(self.width()),
            y1: (y0 + self.tile_size()).min(self.height()),
        }
    }

    /// The whole target.
    #[must_use]
    pub const fn target_rect(&self) -> TileRect {
        TileRect { x0: 0, y0: 0, x1: self.width(), y1: self.height() }
    }

    /// The guard-band factors `[g_x, g_y]` for [`crate::front::clip`](mod@crate::front::clip): NDC `|x| ≤ g_x`
    /// keeps the pixel coordinate inside `±2^GUARD_BITS`.
    #[must_use]
    pub fn guard(&self) -> [f64; 2] {
        let reach = f64::from(1u32 << (GUARD_BITS + 1));
        let [w, h] = self.view();
        [reach / f64::from(w) - 1.0, reach / f64::from(h) - 1.0]
    }
}
