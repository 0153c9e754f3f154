//! A region of lookups settled at once (`ShadowUnit::settle`, what the
//! shading unit's blocks ask): on small maps whose depths sit a few units
//! apart, a region is settled lit exactly when every lookup in it is lit,
//! and shadowed exactly when every one is shadowed, each lookup decided
//! alone by the shadow unit texel by texel.

use glam::Mat4;
use proptest::prelude::*;
use umbra::core::depth::PlaneZ;
use umbra::core::shade::{MapUnit, Normals, ShadeConfig, ShadowUnit};
use umbra::core::shadow::{Bias, DepthTest, Filter, Lookup, MapCoord, Shadow, ShadowConfig, shadow};
use umbra::core::{D24, DepthFormat, NoProbe};

use super::shadow_unit::Map;

/// The map's side, texels (tiles of 8).
const SIDE: u32 = 16;

/// One unit of the 24-bit format in [`PlaneZ`] bits.
const UNIT: i64 = 1 << 32;

/// The depth levels the map's texels take: a few, and some one unit apart,
/// so that receivers meet references exactly and by a unit either side.
fn level(k: u8) -> f32 {
    let unit = 1.0 / 16_777_215.0;
    [0.25, 0.25 + unit, 0.5, 0.5 + 2.0 * unit, 0.75][usize::from(k % 5)]
}

fn shade_config(shadow: ShadowConfig) -> ShadeConfig {
    ShadeConfig {
        camera: Mat4::IDENTITY,
        light: Mat4::IDENTITY,
        width: 1,
        height: 1,
        shadow,
        virtual_samples: false,
        normals: Normals::Flat,
        seed: 0,
    }
}

/// The lookups of the region `[lo, hi]` whose footprints together cover
/// every texel any point of it reads (the corners, and a point every texel
/// between them), at both ends of the depth range.
fn lookups(lo: [MapCoord; 2], hi: [MapCoord; 2], z: (i64, i64)) -> Vec<Lookup> {
    let steps = |a: MapCoord, b: MapCoord| {
        let mut v: Vec<MapCoord> = (0..).map(|k| a + MapCoord::from_num(k)).take_while(|&c| c < b).collect();
        v.push(b);
        v
    };
    let mut out = Vec::new();
    for &x in &steps(lo[0], hi[0]) {
        for &y in &steps(lo[1], hi[1]) {
            for depth in [z.0, z.1] {
                let z = PlaneZ::from_bits(depth);
                out.push(Lookup { x, y, z, footprint: [MapCoord::ZERO; 2], seed: 0, slope: None });
            }
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Settled lit iff every lookup is lit, shadowed iff every lookup is
    /// shadowed, for a constant bias; with a bias range (each sample draws
    /// its own), a settled region is still every lookup's fraction.
    #[test]
    fn a_settled_region_is_every_lookups_fraction(
        z1 in proptest::collection::vec(0u8..5, (SIDE * SIDE) as usize),
        behind in proptest::collection::vec(0u8..5, (SIDE * SIDE) as usize),
        test in 0usize..4,
        bias in 0usize..3,
        size in prop::sample::select(vec![1u8, 2, 3, 5]),
        lo in (-48i32..(SIDE as i32 + 8) * 16, -48i32..(SIDE as i32 + 8) * 16),
        extent in (0i32..96, 0i32..96),
        receiver in (0u8..5, -3i64..4, 0i64..4, 0u32..u32::MAX),
    ) {
        let z1f: Vec<f32> = z1.iter().map(|&k| level(k)).collect();
        // The second depth lies at or behind the first.
        let z2f: Vec<f32> = z1f.iter().zip(&behind).map(|(&a, &k)| a.max(level(k))).collect();
        let map = Map::<D24>::new(SIDE, SIDE, &z1f, &z2f);
        let test = [DepthTest::First, DepthTest::Second, DepthTest::Midpoint, DepthTest::Dual { offset: D24::plane_z(0.1) }][test];
        let bias = [Bias::ZERO, Bias::Constant(D24::plane_z(1.0 / 16_777_215.0)), Bias::Range { lo: PlaneZ::ZERO, hi: D24::plane_z(0.3) }][bias];
        let shadow_cfg = ShadowConfig::new(test, bias, Filter::Box { size }, true).expect("valid");
        // Sixteenths of a texel.
        let at = |v: i32| MapCoord::from_bits(v << 12);
        let (lo, hi) = ([at(lo.0), at(lo.1)], [at(lo.0 + extent.0), at(lo.1 + extent.1)]);
        let (k, units, span, fraction) = receiver;
        let z_lo = D24::widen(D24::quantize(level(k))) + units * UNIT + i64::from(fraction);
        let z = (z_lo, z_lo + span * UNIT);
        let settled = MapUnit.settle(&map.view(), &shade_config(shadow_cfg), lo, hi, z);
        let each: Vec<Shadow> = lookups(lo, hi, z).iter().map(|l| shadow(&map.view(), &shadow_cfg, l, &mut NoProbe)).collect();
        let all = |s: Shadow| each.iter().all(|&f| f == s);
        if let Some(s) = settled {
            prop_assert!(all(s), "settled {s} but the lookups give {each:?}");
        }
        if matches!(bias, Bias::Constant(_)) {
            prop_assert_eq!(settled == Some(Shadow::ZERO), all(Shadow::ZERO), "lit");
            prop_assert_eq!(settled == Some(Shadow::ONE), all(Shadow::ONE), "shadowed");
        }
    }
}
