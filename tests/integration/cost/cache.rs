//! The cache model: LRU worked by hand, and the camera pass's map traffic
//! bounded by a one-line cache above and a cache larger than the map below.

use std::collections::HashSet;

use umbra::core::probe::{Probe, TexelRead};
use umbra::core::shadow::{Bias, DepthTest, Filter, ShadowConfig};
use umbra::core::{CullMode, D24, DepthUnit, LightPassConfig, RasterConfig};
use umbra::sim::cost::cache::{Cache, CacheError, MapCache};
use umbra::sim::pass::camera::CameraFrame;
use umbra::sim::pass::light::{LightMaps, LightOptions};

use crate::common::camera_image;
use umbra::sim::world::scene::Scene;

/// Two sets of two 16-byte ways; lines 0, 2 and 4 share set 0. Line 4
/// evicts line 2 (line 0 was touched since), line 2 then evicts line 0,
/// so line 0 misses again; line 1 lives in set 1.
#[test]
fn lru_by_hand() {
    let mut c = Cache::new(64, 16, 2).expect("valid");
    let hits: Vec<bool> = [0u64, 32, 0, 64, 32, 0, 16, 17].iter().map(|&a| c.access(a)).collect();
    assert_eq!(hits, [false, false, true, false, false, false, false, true]);
    assert_eq!((c.hits, c.misses, c.fetched_bytes()), (2, 6, 96));
    assert_eq!(Cache::new(64, 12, 2).err(), Some(CacheError::Geometry { size: 64, line: 12, ways: 2 }));
    assert!(Cache::new(48, 16, 2).is_err());
}

/// Records every texel read (to count the distinct lines independently).
#[derive(Default)]
pub(super) struct Reads(pub(super) Vec<TexelRead>);

impl Probe for Reads {
    const TEXELS: bool = true;
    fn texel_read(&mut self, r: TexelRead) {
        self.0.push(r);
    }
}

#[test]
fn a_one_line_cache_and_a_whole_map_cache_bound_the_traffic() {
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let raster = RasterConfig::new(256, 256, 32, 8).expect("valid");
    let config = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let (maps, _) = LightMaps::draw::<D24, _>(
        config,
        &scene.draws(scene.light().view_projection(), CullMode::None),
        LightOptions::default(),
        umbra::core::NoProbe,
    )
    .expect("renders");
    let shadow = ShadowConfig::new(DepthTest::Midpoint, Bias::ZERO, Filter::Box { size: 3 }, false).expect("valid");
    let (w, h) = (160, 90);
    let mut reads = Reads::default();
    camera_image::<D24, _>(&mut CameraFrame::default(), &scene, &maps, (shadow, false), (w, h), &mut reads);
    let run = |cache: Cache| {
        let mut probe = MapCache::new(cache, 2, 4);
        camera_image::<D24, _>(&mut CameraFrame::default(), &scene, &maps, (shadow, false), (w, h), &mut probe);
        probe
    };
    let one_line = run(Cache::new(64, 64, 1).expect("valid"));
    let small = run(Cache::new(4096, 64, 4).expect("valid"));
    let whole = run(Cache::new(1 << 20, 64, 16).expect("valid"));
    let lines: HashSet<u64> = reads.0.iter().map(|r| one_line.address(*r) / 64).collect();
    // Midpoint reads both buffers at every sample.
    assert_eq!(one_line.cache.hits + one_line.cache.misses, reads.0.len() as u64);
    assert!(reads.0.len() > 10_000);
    // Larger than the map: only compulsory misses, one per distinct line.
    assert_eq!(whole.cache.misses, lines.len() as u64);
    assert!(one_line.cache.fetched_bytes() >= small.cache.fetched_bytes());
    assert!(small.cache.fetched_bytes() >= whole.cache.fetched_bytes());
    assert!(one_line.cache.fetched_bytes() > 2 * whole.cache.fetched_bytes(), "locality must show");
}

/// Morton order worked by hand: (3, 5) interleaves x = 011 and y = 101 to
/// 100111 = 39; a dual map of 2-byte texels puts its z2 at (39·2 + 1)·2.
#[test]
fn maps_are_swizzled_with_both_depths_side_by_side() {
    use umbra::core::probe::Buffer;
    use umbra::sim::cost::cache::morton;
    assert_eq!(morton(3, 5), 39);
    assert_eq!(morton(0xFFFF, 0), 0x5555_5555);
    // Every byte of both coordinates, against the interleave bit by bit.
    let by_bits = |x: u32, y: u32| {
        (0..32).fold(0u64, |m, b| m | u64::from(x >> b & 1) << (2 * b) | u64::from(y >> b & 1) << (2 * b + 1))
    };
    for (x, y) in [(u32::MAX, 0), (0, u32::MAX), (0x8040_2010, 0x0102_0408), (0xdead_beef, 0x1234_5678), (8191, 4097)] {
        assert_eq!(morton(x, y), by_bits(x, y), "({x:#x}, {y:#x})");
    }
    let m = MapCache::new(Cache::new(64, 64, 1).expect("valid"), 2, 2);
    assert_eq!(m.address(TexelRead { buffer: Buffer::Z2, x: 3, y: 5 }), 158);
    assert_eq!(m.address(TexelRead { buffer: Buffer::Z1, x: 3, y: 5 }), 156);
    let single = MapCache::new(Cache::new(64, 64, 1).expect("valid"), 1, 2);
    assert_eq!(single.address(TexelRead { buffer: Buffer::Z1, x: 3, y: 5 }), 78);
}
