//! The RAM the core's light pass needs, derived from its buffer types.
//!
//! A light pass ([`umbra_core::LightBuffers`]) owns nothing: the caller
//! provides, for a `W × H` map of `T × T`-pixel tiles (`n = ⌈W/T⌉·⌈H/T⌉`
//! tiles), bins of capacity `B` and a setup store of `S` entries:
//!
//! | buffer | bytes |
//! |---|---|
//! | maps `z1` (and `z2` for the dual unit) | `W·H · t · u`, `t` = 2 (D16) or 4 (D24 in a `u32`, F32), `u` = 1 or 2 buffers |
//! | tile summaries ([`umbra_core::TileState`]) | `n · ⌈(5t + 8) / 4⌉·4`: five depths and two `u32` counters |
//! | bins ([`umbra_core::raster::bin::Bin`], a `heapless::Vec<u16, B>`) | `n · ⌈(p + 2B) / p⌉·p`, `p` the pointer width (its length is a `usize`) |
//! | setup store ([`umbra_core::front::setup::Setup`]) | `S · 160`: three edges of three `i64` (72), the depth plane of three `i128` (48), a bounding box of four `u32` (16), two `I32F32` depth bounds (16) and the id (4), padded to a multiple of 8 (ARM) or 16 (x86-64): 160 on both |
//!
//! On Cortex-M `p = 4`; on x86-64 `p = 8`.
//!
//! The camera pass streamed by tile ([`umbra_core::shade::stream`]) needs,
//! for a camera tile of `C × C` pixels, one tile of everything, whatever
//! the image's size (the setup store is shared with the light pass):
//!
//! | buffer | bytes |
//! |---|---|
//! | visibility depth and ids | `C² · (t + 4)` |
//! | one tile summary, one bin | `⌈(5t + 8) / 4⌉·4 + ⌈(p + 2B) / p⌉·p` |
//! | the shading unit's setup store ([`umbra_core::shade::ShadeSetup`]) | `K · 416`: the triangle's interpolation planes in integers and its map-space setup |
//! | one tile of results ([`umbra_core::shade::Shaded`]) | `C² · 40` |
//!
//! The driver keeps the vertex cache ([`umbra_core::front::vertex::VertexCache`],
//! `V · 36` bytes for `V` entries) where the caller puts it, and the
//! clipper's scratch on the stack: two polygons of at most
//! [`umbra_core::front::clip::MAX_POLYGON`] (nine) vertices of four `f64`,
//! [`CLIP_POLYGON_BYTES`] each — a bound the six clip planes set, not a
//! choice.

use umbra_core::{ConfigError, DepthFormatKind, DepthUnit, RasterConfig};

/// Bytes of one entry of the setup store.
/// `72 + 48 + 16 + 16 + 4 = 156`, padded to 160.
pub const SETUP_BYTES: usize = (3 * 3 * 8 + 3 * 16 + 4 * 4 + 2 * 8 + 4_usize).div_ceil(16) * 16;

/// Bytes of one entry of the shading unit's setup store.
pub const SHADE_SETUP_BYTES: usize = 416;
/// Bytes of one pixel's result.
pub const SHADED_BYTES: usize = 40;
/// Bytes of one vertex-cache entry: a `u32` tag and an optional snapped
/// vertex (three 64-bit words and the option's word).
pub const VERTEX_CACHE_ENTRY_BYTES: usize = 4 + 32;

/// Bytes of one of the clipper's polygons: nine vertices of 32 bytes and
/// the length, padded to the vertices' 8-byte alignment.
pub const CLIP_POLYGON_BYTES: usize = (umbra_core::front::clip::MAX_POLYGON * 32 + POINTER_BYTES).div_ceil(8) * 8;

/// The pointer width of the target this is compiled for, bytes.
pub const POINTER_BYTES: usize = core::mem::size_of::<usize>();

/// A light pass's shape, as far as its memory goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FootprintConfig {
    /// Map width, texels.
    pub width: u32,
    /// Map height, texels.
    pub height: u32,
    /// Tile side, pixels (a power of two in `8..=128`).
    pub tile: u32,
    /// Depth format.
    pub format: DepthFormatKind,
    /// Single or dual depth unit.
    pub unit: DepthUnit,
    /// Bin capacity `B`, triangles.
    pub bin_capacity: usize,
    /// Setup-store entries `S`.
    pub setups: usize,
    /// Pointer width of the target, bytes (4 on Cortex-M).
    pub pointer_bytes: usize,
}

/// The light pass's buffers, bytes each.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Footprint {
    /// `z1` and, for the dual unit, `z2`.
    pub maps: usize,
    /// Tile summaries.
    pub tiles: usize,
    /// Bins.
    pub bins: usize,
    /// The setup store.
    pub setups: usize,
}

impl Footprint {
    /// All of it.
    #[must_use]
    pub const fn total(&self) -> usize {
        self.maps + self.tiles + self.bins + self.setups
    }
}

/// Bytes of one texel in the caller's buffer (not on the wire: D24 moves 3).
#[must_use]
pub const fn texel_bytes(format: DepthFormatKind) -> usize {
    match format {
        DepthFormatKind::D16 => 2,
        DepthFormatKind::D24 | DepthFormatKind::F32 => 4,
    }
}

/// Bytes of one tile summary for texels of `t` bytes.
#[must_use]
pub const fn tile_state_bytes(t: usize) -> usize {
    (5 * t + 8).div_ceil(4) * 4
}

/// Bytes of one bin of capacity `b` with a `p`-byte length field.
#[must_use]
pub const fn bin_bytes(b: usize, p: usize) -> usize {
    (p + 2 * b).div_ceil(p) * p
}

/// The RAM of a light pass with this shape.
///
/// # Errors
/// The [`ConfigError`] of [`RasterConfig::new`] for a map or tile size the
/// core does not accept.
pub fn light_pass(cfg: &FootprintConfig) -> Result<Footprint, ConfigError> {
    let raster = RasterConfig::new(cfg.width, cfg.height, cfg.tile, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    let t = texel_bytes(cfg.format);
    let n = raster.tile_count();
    let buffers = match cfg.unit {
        DepthUnit::Single => 1,
        DepthUnit::Dual => 2,
    };
    Ok(Footprint {
        maps: raster.texel_count() * t * buffers,
        tiles: n * tile_state_bytes(t),
        bins: n * bin_bytes(cfg.bin_capacity, cfg.pointer_bytes),
        setups: cfg.setups * SETUP_BYTES,
    })
}

/// A camera pass streamed by tile, as far as its memory goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CameraFootprint {
    /// Camera tile side `C`, pixels.
    pub tile: u32,
    /// The visibility unit's depth format.
    pub format: DepthFormatKind,
    /// Bin capacity `B`, triangles.
    pub bin_capacity: usize,
    /// The shading unit's setup-store entries `K`.
    pub shade_setups: usize,
    /// Pointer width of the target, bytes.
    pub pointer_bytes: usize,
}

/// The streamed camera pass's buffers, bytes each.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CameraBuffers {
    /// Visibility depth and ids of one tile.
    pub visibility: usize,
    /// One tile summary and one bin.
    pub tile: usize,
    /// The shading unit's setup store.
    pub shade_setups: usize,
    /// One tile of results.
    pub results: usize,
}

impl CameraBuffers {
    /// All of it.
    #[must_use]
    pub const fn total(&self) -> usize {
        self.visibility + self.tile + self.shade_setups + self.results
    }
}

/// The RAM of a camera pass streamed by tile with this shape.
///
/// # Errors
/// [`ConfigError::TileSize`] for a tile side the core does not accept.
pub fn camera_pass(cfg: &CameraFootprint) -> Result<CameraBuffers, ConfigError> {
    let raster = RasterConfig::new(cfg.tile, cfg.tile, cfg.tile, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    let (pixels, t) = (raster.texel_count(), texel_bytes(cfg.format));
    Ok(CameraBuffers {
        visibility: pixels * (t + 4),
        tile: tile_state_bytes(t) + bin_bytes(cfg.bin_capacity, cfg.pointer_bytes),
        shade_setups: cfg.shade_setups * SHADE_SETUP_BYTES,
        results: pixels * SHADED_BYTES,
    })
}

#[cfg(test)]
mod tests {
    use core::mem::size_of;

    use umbra_core::front::setup::Setup;
    use umbra_core::raster::bin::Bin;
    use umbra_core::{DepthFormatKind, DepthUnit, TileState};

    use super::*;

    #[test]
    fn camera_element_sizes_match_the_types() {
        use umbra_core::front::vertex::VertexCache;
        use umbra_core::shade::{ShadeSetup, Shaded};
        assert_eq!(SHADE_SETUP_BYTES, size_of::<ShadeSetup>());
        assert_eq!(SHADED_BYTES, size_of::<Shaded>());
        assert_eq!(16 * VERTEX_CACHE_ENTRY_BYTES, size_of::<VertexCache<16>>());
        assert_eq!(CLIP_POLYGON_BYTES, size_of::<umbra_core::front::clip::Polygon>());
        let cfg = CameraFootprint {
            tile: 8,
            format: DepthFormatKind::D24,
            bin_capacity: 16,
            shade_setups: 1,
            pointer_bytes: POINTER_BYTES,
        };
        // By hand: 64 · 8 + 28 + (p + 32), 416, 64 · 40.
        let f = camera_pass(&cfg).unwrap();
        assert_eq!(f.visibility, 512);
        assert_eq!(f.tile, 28 + bin_bytes(16, POINTER_BYTES));
        assert_eq!((f.shade_setups, f.results), (416, 2560));
    }

    #[test]
    fn element_sizes_match_the_types() {
        assert_eq!(SETUP_BYTES, size_of::<Setup>());
        assert_eq!(tile_state_bytes(2), size_of::<TileState<u16>>());
        assert_eq!(tile_state_bytes(4), size_of::<TileState<u32>>());
        assert_eq!(texel_bytes(DepthFormatKind::D16), size_of::<<umbra_core::D16 as umbra_core::DepthFormat>::Texel>());
        assert_eq!(texel_bytes(DepthFormatKind::D24), size_of::<<umbra_core::D24 as umbra_core::DepthFormat>::Texel>());
        assert_eq!(bin_bytes(1, POINTER_BYTES), size_of::<Bin<1>>());
        assert_eq!(bin_bytes(16, POINTER_BYTES), size_of::<Bin<16>>());
        assert_eq!(bin_bytes(64, POINTER_BYTES), size_of::<Bin<64>>());
        assert_eq!(bin_bytes(255, POINTER_BYTES), size_of::<Bin<255>>());
    }

    #[test]
    fn whole_buffers_match_arrays_of_the_types() {
        let cfg = FootprintConfig {
            width: 64,
            height: 40,
            tile: 16,
            format: DepthFormatKind::D16,
            unit: DepthUnit::Dual,
            bin_capacity: 16,
            setups: 32,
            pointer_bytes: POINTER_BYTES,
        };
        let f = light_pass(&cfg).unwrap();
        // 4 × 3 tiles (the last row partial).
        assert_eq!(f.maps, 2 * size_of::<[u16; 64 * 40]>());
        assert_eq!(f.tiles, size_of::<[TileState<u16>; 12]>());
        assert_eq!(f.bins, size_of::<[Bin<16>; 12]>());
        assert_eq!(f.setups, size_of::<[Setup; 32]>());
    }

    /// The demo's light pass on Cortex-M, by hand: maps 2 · 4096 · 2,
    /// 16 tiles of 20 bytes, 16 bins of 4 + 32 bytes, 32 setups of 160.
    #[test]
    fn hand_computed_cortex_m() {
        let cfg = FootprintConfig {
            width: 64,
            height: 64,
            tile: 16,
            format: DepthFormatKind::D16,
            unit: DepthUnit::Dual,
            bin_capacity: 16,
            setups: 32,
            pointer_bytes: 4,
        };
        let f = light_pass(&cfg).unwrap();
        assert_eq!(f, Footprint { maps: 16_384, tiles: 320, bins: 576, setups: 5_120 });
        assert_eq!(f.total(), 22_400);
        // 1024², d24 single, 32-pixel tiles, bins of 64, 256 setups:
        // 4 MiB + 1024 · 28 + 1024 · 132 + 256 · 160.
        let big = FootprintConfig {
            width: 1024,
            height: 1024,
            tile: 32,
            format: DepthFormatKind::D24,
            unit: DepthUnit::Single,
            bin_capacity: 64,
            setups: 256,
            ..cfg
        };
        assert_eq!(light_pass(&big).unwrap().total(), 4_194_304 + 28_672 + 135_168 + 40_960);
    }

    /// A row of the README's table: 256², 16-pixel tiles, D16 dual, bins of
    /// 64, 256 setups, Cortex-M: maps 256·256·2·2, 256 tiles of 20 bytes,
    /// 256 bins of 4 + 128 bytes, 256 setups of 160.
    #[test]
    fn readme_row() {
        let cfg = FootprintConfig {
            width: 256,
            height: 256,
            tile: 16,
            format: DepthFormatKind::D16,
            unit: DepthUnit::Dual,
            bin_capacity: 64,
            setups: 256,
            pointer_bytes: 4,
        };
        assert_eq!(light_pass(&cfg).unwrap().total(), 262_144 + 5_120 + 33_792 + 40_960);
        assert_eq!(light_pass(&cfg).unwrap().total(), 342_016);
    }

    #[test]
    fn bad_tile_size_is_an_error() {
        let cfg = FootprintConfig {
            width: 64,
            height: 64,
            tile: 12,
            format: DepthFormatKind::D16,
            unit: DepthUnit::Single,
            bin_capacity: 1,
            setups: 1,
            pointer_bytes: 4,
        };
        assert_eq!(light_pass(&cfg), Err(ConfigError::TileSize { size: 12 }));
    }
}
