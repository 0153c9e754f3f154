#![no_std]
#![forbid(unsafe_code)]
#![doc = include_str!("../README.md")]

pub mod checksum;
pub mod footprint;
mod render;
pub mod scene;

use core::fmt;
use core::mem::size_of;

use umbra_core::depth::PlaneZ;
use umbra_core::front::setup::{DepthPlane, Edge, Setup};
use umbra_core::front::vertex::VertexCache;
use umbra_core::glam::Vec3;
use umbra_core::raster::bin::Bin;
use umbra_core::shade::stream::StreamError;
use umbra_core::shade::{Normals, ShadeConfig, ShadeSetup, Shaded};
use umbra_core::shadow::{Bias, DepthTest, Filter, Shadow, ShadowConfig, ShadowConfigError};
use umbra_core::{ConfigError, DepthUnit, LightPassConfig, RasterConfig, SubmitError, TileState};

pub use checksum::{CameraChecksum, Fnv1a, map_checksum};
pub use render::{render, render_uncounted_with, render_with};
pub use umbra_core::probe::Totals;

/// Map side of the full demo, texels.
pub const MAP: u32 = 64;
/// Camera image side, pixels (the camera pass streams it by tile, so its
/// size costs no RAM).
pub const IMAGE: u32 = 64;
/// Tile side of the light pass, texels.
pub const TILE: u32 = 16;
/// Tile side of the camera pass, pixels: the unit it streams in.
pub const CAMERA_TILE: u32 = 8;
/// Bin capacity: small, so that full bins flush early.
pub const BIN_CAPACITY: usize = 16;
/// Setup-store entries of the full demo: fewer than the scene's
/// triangles, so the store fills and every bin is drained once mid-pass.
pub const SETUPS: usize = 16;
/// Post-transform vertex-cache entries.
pub const VERTEX_CACHE: usize = 16;
/// The shading unit's setup-store entries: none kept in the demo's
/// memory (an entry is 416 bytes, and the unit then keeps the one it works
/// on, on the stack).
pub const SHADE_SETUPS: usize = 0;
/// Seed of the shading unit's per-pixel random numbers.
pub const SEED: u64 = 0x5eed;

/// Pixels of one camera tile.
pub const CAMERA_TILE_TEXELS: usize = (CAMERA_TILE * CAMERA_TILE) as usize;

/// A pixel result with every byte zero, so that a `static` [`Memory`] is
/// zero-initialised (no flash image).
const ZERO_PIXEL: Shaded = Shaded { triangle: 0, light: None, normal: Vec3::ZERO, shadow: Shadow::ZERO };

/// A setup-store entry with every byte zero (the store is written before
/// it is read).
const ZERO_SETUP: Setup = Setup {
    edges: [Edge { dx: 0, dy: 0, c: 0 }; 3],
    plane: DepthPlane { a: 0, b: 0, c: 0 },
    bbox: umbra_core::TileRect { x0: 0, y0: 0, x1: 0, y1: 0 },
    z_min: PlaneZ::ZERO,
    z_max: PlaneZ::ZERO,
    triangle: 0,
};

/// Every buffer of both passes for a map of `MAP_TEXELS` texels in
/// `MAP_TILES` tiles, with a setup store of `SETUPS` entries: the maps and their tiles, and one camera tile of
/// everything (the camera pass is streamed by tile, so no buffer the size
/// of the image exists). The setup store is shared: the camera pass starts
/// after the light pass has drained it.
pub struct Memory<const MAP_TEXELS: usize, const MAP_TILES: usize, const SETUPS: usize> {
    z1: [u16; MAP_TEXELS],
    z2: [u16; MAP_TEXELS],
    map_tiles: [TileState<u16>; MAP_TILES],
    bins: [Bin<BIN_CAPACITY>; MAP_TILES],
    setups: [Setup; SETUPS],
    cache: VertexCache<VERTEX_CACHE>,
    depth: [u32; CAMERA_TILE_TEXELS],
    ids: [u32; CAMERA_TILE_TEXELS],
    camera_tile: [TileState<u32>; 1],
    camera_bin: [Bin<BIN_CAPACITY>; 1],
    shade_setups: [ShadeSetup; SHADE_SETUPS],
    pixels: [Shaded; CAMERA_TILE_TEXELS],
    light: Totals,
    camera: Totals,
}

/// The full demo's memory: a 64² map, 16 setups.
pub type Full = Memory<{ 64 * 64 }, 16, SETUPS>;
/// The largest demo a part of 16 KiB of RAM holds beside its stack: a 32²
/// map and 4 setups, 612 bytes to spare on the Cortex-M0 (a 36² map needs
/// 1,368 bytes more, 8 setups 640).
pub type Small = Memory<{ 32 * 32 }, 4, 4>;

impl<const MAP_TEXELS: usize, const MAP_TILES: usize, const SETUPS: usize> Default
    for Memory<MAP_TEXELS, MAP_TILES, SETUPS>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<const MAP_TEXELS: usize, const MAP_TILES: usize, const SETUPS: usize> Memory<MAP_TEXELS, MAP_TILES, SETUPS> {
    /// The map's side: the square root of `MAP_TEXELS`.
    pub const MAP_SIDE: u32 = {
        let mut side = 0u32;
        while ((side + 1) * (side + 1)) as usize <= MAP_TEXELS {
            side += 1;
        }
        side
    };

    /// Texels of the map.
    pub const MAP_TEXELS: usize = MAP_TEXELS;
    /// Tiles of the map.
    pub const MAP_TILES: usize = MAP_TILES;
    /// Setup-store entries.
    pub const SETUPS: usize = SETUPS;

    /// All buffers zeroed (a `const`, so it can initialise a `static`).
    #[must_use]
    pub const fn new() -> Self {
        Self {
            z1: [0; MAP_TEXELS],
            z2: [0; MAP_TEXELS],
            map_tiles: [TileState::cleared(0, 0); MAP_TILES],
            bins: [const { Bin::new() }; MAP_TILES],
            setups: [ZERO_SETUP; SETUPS],
            cache: VertexCache::new(),
            depth: [0; CAMERA_TILE_TEXELS],
            ids: [0; CAMERA_TILE_TEXELS],
            camera_tile: [TileState::cleared(0, 0)],
            camera_bin: [const { Bin::new() }],
            shade_setups: [ShadeSetup::EMPTY; SHADE_SETUPS],
            pixels: [ZERO_PIXEL; CAMERA_TILE_TEXELS],
            light: Totals::ZERO,
            camera: Totals::ZERO,
        }
    }

    /// The event totals of the last [`render`]: the light pass's, and the
    /// camera pass's (visibility and shading).
    #[must_use]
    pub const fn totals(&self) -> (&Totals, &Totals) {
        (&self.light, &self.camera)
    }

    /// The light pass's nearest and second-nearest depths, row-major.
    #[must_use]
    pub const fn maps(&self) -> (&[u16], &[u16]) {
        (&self.z1, &self.z2)
    }
}

/// The demo's light pass as [`footprint::light_pass`] describes it, for a
/// map of side `map` and `setups` setup-store entries, on the target this
/// is compiled for.
#[must_use]
pub const fn light_footprint_config(map: u32, setups: usize) -> footprint::FootprintConfig {
    footprint::FootprintConfig {
        width: map,
        height: map,
        tile: TILE,
        format: umbra_core::DepthFormatKind::D16,
        unit: DepthUnit::Dual,
        bin_capacity: BIN_CAPACITY,
        setups,
        pointer_bytes: footprint::POINTER_BYTES,
    }
}

/// The demo's camera pass as [`footprint::camera_pass`] describes it.
#[must_use]
pub const fn camera_footprint_config() -> footprint::CameraFootprint {
    footprint::CameraFootprint {
        tile: CAMERA_TILE,
        format: umbra_core::DepthFormatKind::D24,
        bin_capacity: BIN_CAPACITY,
        shade_setups: SHADE_SETUPS,
        pointer_bytes: footprint::POINTER_BYTES,
    }
}

/// Bytes of every buffer the demo's two passes use, from `size_of` of
/// their types on the target this is compiled for: what the footprint
/// formulas must predict (the vertex cache besides).
#[must_use]
pub const fn buffer_bytes<const MAP_TEXELS: usize, const MAP_TILES: usize, const SETUPS: usize>() -> (usize, usize) {
    let light = 2 * size_of::<[u16; MAP_TEXELS]>()
        + size_of::<[TileState<u16>; MAP_TILES]>()
        + size_of::<[Bin<BIN_CAPACITY>; MAP_TILES]>()
        + size_of::<[Setup; SETUPS]>();
    let camera = size_of::<[u32; CAMERA_TILE_TEXELS]>() * 2
        + size_of::<[TileState<u32>; 1]>()
        + size_of::<[Bin<BIN_CAPACITY>; 1]>()
        + size_of::<[ShadeSetup; SHADE_SETUPS]>()
        + size_of::<[Shaded; CAMERA_TILE_TEXELS]>();
    (light, camera)
}

/// What [`render`] reports (the event totals stay in the [`Memory`]: they
/// are large for a microcontroller's stack).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Summary {
    /// FNV-1a 64 of the light pass's maps: every `z1` texel, then every
    /// `z2` texel, row-major, each as 2 little-endian bytes.
    pub map_checksum: u64,
    /// FNV-1a 64 of the camera pass, per pixel in the order the streamed
    /// pass makes them (8×8 tiles row-major, pixels row-major in a tile):
    /// the triangle id
    /// (`u32`); then `0u8` when there is no light point, or `1u8` and the
    /// point's `x`, `y` (`i32` bits of 16.16 texels) and `z` (`i64` bits of
    /// 32.32 LSBs); then the shadow fraction (`u32` bits of 16.16).
    /// Integers are little-endian.
    pub camera_checksum: u64,
    /// Pixels the camera sees the scene in.
    pub covered: u32,
    /// Covered pixels wholly in shadow.
    pub shadowed: u32,
}

/// Why the demo could not render (none of these happens with the bundled
/// scene; they are the core's errors, passed on).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum DemoError {
    /// A configuration or buffer the core rejected.
    Config(ConfigError),
    /// A malformed mesh.
    Submit(SubmitError),
    /// A shadow configuration the core rejected.
    Shadow(ShadowConfigError),
}

impl fmt::Display for DemoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Config(e) => write!(f, "demo configuration: {e}"),
            Self::Submit(e) => write!(f, "demo scene: {e}"),
            Self::Shadow(e) => write!(f, "demo shadow unit: {e}"),
        }
    }
}

impl core::error::Error for DemoError {}

impl From<ConfigError> for DemoError {
    fn from(e: ConfigError) -> Self {
        Self::Config(e)
    }
}

impl From<SubmitError> for DemoError {
    fn from(e: SubmitError) -> Self {
        Self::Submit(e)
    }
}

impl From<StreamError> for DemoError {
    fn from(e: StreamError) -> Self {
        match e {
            StreamError::Submit(e) => Self::Submit(e),
            StreamError::Config(e) => Self::Config(e),
            _ => Self::Config(ConfigError::Window { x0: 0, y0: 0, width: IMAGE, height: IMAGE }),
        }
    }
}

impl From<ShadowConfigError> for DemoError {
    fn from(e: ShadowConfigError) -> Self {
        Self::Shadow(e)
    }
}

/// The light pass's configuration: a `map`² map, 16-pixel tiles, dual
/// depth unit, max-z culling.
///
/// # Errors
/// A map side the core refuses.
pub fn light_config(map: u32) -> Result<LightPassConfig, ConfigError> {
    let raster = RasterConfig::new(map, map, TILE, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    Ok(LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true })
}

/// The shadow unit's configuration: second depth (Wang & Molnar 1994 §3.1),
/// no bias, 2×2 box filter, lookups culled by the tiles' bounds.
///
/// # Errors
/// None for the constants here; the core's check is kept.
pub fn shadow_config() -> Result<ShadowConfig, ShadowConfigError> {
    ShadowConfig::new(DepthTest::Second, Bias::ZERO, Filter::Box { size: 2 }, true)
}

/// The shading configuration of the camera pass against a map of side
/// `map` (the light matrix does not depend on it).
///
/// # Errors
/// None for the constants here; the core's check is kept.
pub fn shade_config() -> Result<ShadeConfig, ShadowConfigError> {
    Ok(ShadeConfig {
        camera: scene::camera_matrix(),
        light: scene::light_matrix(),
        width: IMAGE,
        height: IMAGE,
        shadow: shadow_config()?,
        virtual_samples: true,
        normals: Normals::Flat,
        seed: SEED,
    })
}

/// The camera pass's visibility: the `IMAGE`² image in `CAMERA_TILE`-pixel
/// tiles, 24-bit depth, single unit, max-z culling.
///
/// # Errors
/// None for the constants here; the core's check is kept.
pub fn visibility_config() -> Result<LightPassConfig, ConfigError> {
    let raster = RasterConfig::new(IMAGE, IMAGE, CAMERA_TILE, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    Ok(LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true })
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::boxed::Box;
    use std::vec;

    use umbra_core::shade::shade;
    use umbra_core::shadow::MapView;
    use umbra_core::{CullMode, D16, D24, LightBuffers, LightPass};

    use super::*;

    /// The scene is one a shadow test can fail on: the camera sees most of
    /// the image, part of it in shadow and most of it lit; both passes do
    /// the work the configuration asks for.
    #[test]
    fn the_scene_exercises_the_passes() {
        let mut mem = Box::new(Full::new());
        let s = render(&mut mem).unwrap();
        let (light, camera) = mem.totals();
        assert!(s.covered > IMAGE * IMAGE / 2, "{s:?}");
        assert!(s.shadowed > 100 && s.shadowed < s.covered / 2, "{s:?}");
        assert_eq!(light.submitted, scene::TRIANGLES as u64);
        // The camera pass sends the scene once per 8×8 tile.
        assert_eq!(camera.submitted, (scene::TRIANGLES * 64) as u64);
        // Every flush stores its tile; the small setup store makes some
        // tiles flush twice, so they are loaded back.
        assert_eq!(light.flushes(), light.tile_stores);
        assert!(light.tile_loads > 0);
        // The dual unit reads z1 and z2 for every fragment.
        assert_eq!(light.depth_reads(), 2 * light.fragments);
        assert!(camera.virtual_samples > 0 && camera.lookups_culled > 0);
    }

    /// The streamed camera pass gives the full-frame pass's pixels: the
    /// whole image's visibility and shading, through the core's full-frame
    /// units, folded in the same tile order, has the same checksum.
    #[test]
    fn the_streamed_camera_pass_is_the_full_frame_one() {
        for map in [64u32, 32] {
            let (s, z1, z2, tiles) = if map == 64 {
                let mut mem = Box::new(Full::new());
                let s = render(&mut mem).unwrap();
                (s, mem.z1.to_vec(), mem.z2.to_vec(), mem.map_tiles.to_vec())
            } else {
                let mut mem = Box::new(Small::new());
                let s = render(&mut mem).unwrap();
                (s, mem.z1.to_vec(), mem.z2.to_vec(), mem.map_tiles.to_vec())
            };
            let texels = (IMAGE * IMAGE) as usize;
            let vis = visibility_config().unwrap();
            let n = vis.raster.tile_count();
            let (mut depth, mut ids) = (vec![0u32; texels], vec![0u32; texels]);
            let (mut states, mut bins) = (vec![TileState::cleared(0, 0); n], vec![Bin::<BIN_CAPACITY>::new(); n]);
            let mut setups = vec![ZERO_SETUP; 16];
            let buffers = LightBuffers::<D24, BIN_CAPACITY> {
                z1: &mut depth,
                z2: &mut [],
                ids: &mut ids,
                tiles: &mut states,
                bins: &mut bins,
                setups: &mut setups,
            };
            let mut pass = LightPass::<D24, Totals, BIN_CAPACITY>::new(vis, buffers, Totals::default()).unwrap();
            pass.draw_mesh(&scene::POSITIONS, &scene::INDICES, &scene::camera_matrix(), CullMode::None).unwrap();
            pass.finish();
            let view = MapView::<D16>::new(light_config(map).unwrap().raster, &z1, &z2, &tiles).unwrap();
            let mut out = vec![Shaded::BACKGROUND; texels];
            shade(&shade_config().unwrap(), &ids, &view, &scene::triangle, &mut out, &mut Totals::default()).unwrap();
            let mut whole = CameraChecksum::new();
            for t in 0..n {
                let r = vis.raster.tile_rect(vis.raster.tile_id(t));
                let tile: std::vec::Vec<Shaded> = (r.y0..r.y1)
                    .flat_map(|y| (r.x0..r.x1).map(move |x| (y * IMAGE + x) as usize))
                    .map(|i| out[i])
                    .collect();
                whole.tile(r, &tile);
            }
            assert_eq!((whole.finish(), whole.covered, whole.shadowed), (s.camera_checksum, s.covered, s.shadowed));
        }
    }

    /// Without the counters the render is the same bits, and the totals
    /// are left as they were.
    #[test]
    fn the_uncounted_render_is_the_counted_one() {
        let mut mem = Box::new(Full::new());
        let counted = render(&mut mem).unwrap();
        let totals = *mem.totals().0;
        assert!(totals.fragments > 0);
        let mut fresh = Box::new(Full::new());
        assert_eq!(render_uncounted_with(&mut fresh, || ()).unwrap(), counted);
        assert_eq!(fresh.totals(), (&Totals::ZERO, &Totals::ZERO));
        assert_eq!(render_uncounted_with(&mut mem, || ()).unwrap(), counted);
        assert_eq!(*mem.totals().0, totals);
    }

    #[test]
    fn the_footprint_predicts_the_demo_buffers() {
        let light = footprint::light_pass(&light_footprint_config(MAP, SETUPS)).unwrap();
        let camera = footprint::camera_pass(&camera_footprint_config()).unwrap();
        assert_eq!((light.total(), camera.total()), buffer_bytes::<{ 64 * 64 }, 16, SETUPS>());
        let small = footprint::light_pass(&light_footprint_config(32, 4)).unwrap();
        assert_eq!(small.total(), buffer_bytes::<{ 32 * 32 }, 4, 4>().0);
        assert_eq!((Full::MAP_SIDE, Small::MAP_SIDE), (64, 32));
    }
}
