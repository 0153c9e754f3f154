//! Stack distances against direct simulation: one pass gives, for every
//! capacity from one line to the whole map and every associativity (1, 2,
//! 4 ways and fully associative), the hits a cache of that geometry
//! counts access by access; for numbers of sets that are not a power of
//! two, as the desktop machine's 2 560 are not; and for passes whose fewest
//! sets are several, nested or not.

use umbra::core::shadow::{Bias, DepthTest, Filter, ShadowConfig};
use umbra::core::{CullMode, D24, DepthUnit, LightPassConfig, RasterConfig};
use umbra::sim::cost::cache::{Cache, MapCache};
use umbra::sim::cost::stack::StackDistances;
use umbra::sim::pass::camera::CameraFrame;
use umbra::sim::pass::light::{LightMaps, LightOptions};
use umbra::sim::world::scene::Scene;

use super::cache::Reads;
use crate::common::camera_image;

/// The byte addresses of a camera pass's map reads: a 64² dual map of
/// 4-byte texels (32 KiB, 512 lines of 64 bytes), a 3×3 box at 80×45.
fn map_reads() -> Vec<u64> {
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let raster = RasterConfig::new(64, 64, 32, 8).expect("valid");
    let config = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let draws = scene.draws(scene.light().view_projection(), CullMode::None);
    let (maps, _) =
        LightMaps::draw::<D24, _>(config, &draws, LightOptions::default(), umbra::core::NoProbe).expect("renders");
    let shadow = ShadowConfig::new(DepthTest::Midpoint, Bias::ZERO, Filter::Box { size: 3 }, false).expect("valid");
    let mut reads = Reads::default();
    camera_image::<D24, _>(&mut CameraFrame::default(), &scene, &maps, (shadow, false), (80, 45), &mut reads);
    let swizzle = MapCache::new(Cache::new(64, 64, 1).expect("valid"), 2, 4);
    reads.0.iter().map(|&r| swizzle.address(r)).collect()
}

/// Addresses with conflicts a map's reads rarely make: a linear
/// congruential walk over 4 096 lines, every fourth access near the last.
fn scattered() -> Vec<u64> {
    let mut state = 12_345u64;
    let mut last = 0;
    (0..40_000)
        .map(|i| {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            last = if i % 4 == 0 { (last / 64 + (state >> 60)) % 4_096 * 64 } else { (state >> 40) % 4_096 * 64 };
            last
        })
        .collect()
}

/// Hits of `addresses` through a cache of `lines` 64-byte lines and `ways` ways, access by access.
fn direct(addresses: &[u64], lines: u64, ways: u32) -> u64 {
    let mut c = Cache::new(lines * 64, 64, ways).expect("a geometry");
    addresses.iter().for_each(|&a| {
        c.access(a);
    });
    c.hits
}

#[test]
fn stack_distances_count_what_each_cache_counts() {
    for (name, addresses, whole) in [("map reads", map_reads(), 512u64), ("scattered", scattered(), 4_096)] {
        assert!(addresses.len() > 10_000, "{name}: {} accesses", addresses.len());
        // One pass for every geometry below: up to `whole` sets, up to `whole` ways.
        let mut sets: Vec<u64> = (0..=whole.trailing_zeros()).map(|k| 1 << k).collect();
        sets.extend([3, 24]);
        let mut stack = StackDistances::new(64, &sets, u32::try_from(whole).expect("small")).expect("valid");
        addresses.iter().for_each(|&a| {
            stack.access(a);
        });
        let mut checked = 0;
        let mut capacity = 1;
        while capacity <= whole {
            for ways in [1, 2, 4, capacity] {
                if ways > capacity {
                    continue;
                }
                let w = u32::try_from(ways).expect("small");
                let expected = direct(&addresses, capacity, w);
                assert_eq!(stack.hits(capacity / ways, w), Some(expected), "{name}: {capacity} lines, {ways} ways");
                checked += 1;
            }
            capacity *= 2;
        }
        for (sets, ways) in [(3, 2), (3, 4), (24, 1), (24, 4)] {
            let expected = direct(&addresses, sets * u64::from(ways), ways);
            assert_eq!(stack.hits(sets, ways), Some(expected), "{name}: {sets} sets, {ways} ways");
        }
        // Passes whose fewest sets are more than one: nested (each number a
        // multiple of the fewest, so that a line the most recent of its set
        // there is the most recent in every order) and not.
        for pass in [vec![4, 8, 16, 64], vec![3, 24], vec![3, 4, 24]] {
            let mut stack = StackDistances::new(64, &pass, 4).expect("valid");
            addresses.iter().for_each(|&a| {
                stack.access(a);
            });
            for (&sets, ways) in pass.iter().flat_map(|s| [1, 2, 4].map(|w| (s, w))) {
                let expected = direct(&addresses, sets * u64::from(ways), ways);
                assert_eq!(stack.hits(sets, ways), Some(expected), "{name}: {sets} sets of {pass:?}, {ways} ways");
            }
        }
        // One line to the whole map: 10 capacities for the map, 13 scattered;
        // each direct-mapped, 2-way, 4-way and fully associative where they differ.
        assert!(checked >= 30, "{name}: {checked} geometries");
        // The whole map in one fully associative cache misses once a line.
        let lines: std::collections::HashSet<u64> = addresses.iter().map(|a| a / 64).collect();
        let hits = stack.hits(1, u32::try_from(whole).expect("small")).expect("asked");
        assert_eq!(addresses.len() as u64 - hits, lines.len() as u64, "{name}");
    }
    // Geometries the pass was not asked for are not answered.
    let stack = StackDistances::new(64, &[8, 6], 4).expect("valid");
    assert_eq!(stack.hits(16, 4), None);
    assert_eq!(stack.hits(8, 8), None);
    assert_eq!(stack.hits(4, 2), None);
    assert_eq!(stack.hits(6, 2), Some(0));
    assert!(StackDistances::new(48, &[8], 4).is_err());
    assert!(StackDistances::new(64, &[0], 4).is_err());
}
