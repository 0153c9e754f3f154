//! The shadow unit: depth tests and filters on hand-worked cases from the
//! papers, and invariants on maps from the light pass.

use proptest::prelude::*;
use umbra::core::depth::PlaneZ;
use umbra::core::probe::Totals;
use umbra::core::shadow::{
    Bias, DepthTest, Filter, Jitter, Lookup, MapCoord, MapView, Shadow, ShadowConfig, Slope, TangentPlane, jitter_grid,
    shadow, shadow_with_virtual_samples,
};
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthUnit, NoProbe, RasterConfig, TileState};

use crate::common::{config, run, triangles};

/// A map from rows of depths in `[0, 1]`, with exact tile bounds.
pub(crate) struct Map<F: DepthFormat> {
    raster: RasterConfig,
    z1: Vec<F::Texel>,
    z2: Vec<F::Texel>,
    tiles: Vec<TileState<F::Texel>>,
}

impl<F: DepthFormat> Map<F> {
    pub(crate) fn new(w: u32, h: u32, z1: &[f32], z2: &[f32]) -> Self {
        let raster = RasterConfig::new(w, h, 8, 8).expect("valid");
        let q = |v: &[f32]| v.iter().map(|&z| F::quantize(z)).collect::<Vec<_>>();
        let (z1, z2) = (q(z1), q(z2));
        let tiles = (0..raster.tile_count())
            .map(|i| {
                let r = raster.tile_rect(raster.tile_id(i));
                let mut t = TileState::cleared(F::FAR, r.area());
                let texels: Vec<usize> =
                    (r.y0..r.y1).flat_map(|y| (r.x0..r.x1).map(move |x| (y * w + x) as usize)).collect();
                let bounds = |b: &[F::Texel]| {
                    let v = texels.iter().map(|&i| b.get(i).copied().unwrap_or(F::FAR));
                    (v.clone().min().unwrap_or(F::FAR), v.max().unwrap_or(F::FAR))
                };
                (t.z1_min, t.z1_max) = bounds(&z1);
                (t.z2_min, t.z2_max) = bounds(&z2);
                t
            })
            .collect();
        Self { raster, z1, z2, tiles }
    }

    pub(crate) fn view(&self) -> MapView<'_, F> {
        MapView::new(self.raster, &self.z1, &self.z2, &self.tiles).expect("sized")
    }
}

/// A lookup at map position `(x, y)` and depth `z` in format `F`'s units.
fn at<F: DepthFormat>(x: f32, y: f32, z: f32) -> Lookup {
    let z = F::plane_z(f64::from(z.max(0.0))) - PlaneZ::from_num(u8::from(z < 0.0));
    Lookup {
        x: MapCoord::from_num(x),
        y: MapCoord::from_num(y),
        z,
        footprint: [MapCoord::ZERO; 2],
        seed: 1,
        slope: None,
    }
}

fn cfg(test: DepthTest, filter: Filter) -> ShadowConfig {
    ShadowConfig::new(test, Bias::ZERO, filter, false).expect("valid")
}

/// Reeves et al. 1987, Figure 2: a 3×3 region of the map, a surface at
/// z = 49.8. Averaging the depths first gives 22.9 < 49.8: "100% in
/// shadow"; comparing first gives 5 of 9 in shadow: 0.55.
#[test]
fn reeves_figure_2() {
    let depths = [50.2f32, 50.0, 50.0, 50.1, 1.3, 1.4, 1.2, 1.1, 1.3];
    let mean: f32 = depths.iter().sum::<f32>() / 9.0;
    assert!((mean - 22.9).abs() < 0.1 && mean < 49.8, "ordinary filtering: {mean}");
    let map = Map::<D24>::new(3, 3, &depths.map(|d| d / 100.0), &[]);
    let s =
        shadow(&map.view(), &cfg(DepthTest::First, Filter::Box { size: 3 }), &at::<D24>(1.5, 1.5, 0.498), &mut NoProbe);
    assert_eq!(s, Shadow::from_bits((5 * 65536 + 4) / 9));
    assert!((s.to_num::<f64>() - 0.555).abs() < 0.001);
}

/// z1 = 0.3, z2 = 0.7 everywhere: midpoint 0.5, dual with offset 0.1 → 0.4.
#[test]
fn the_four_depth_tests() {
    let map = Map::<D24>::new(4, 4, &[0.3; 16], &[0.7; 16]);
    let view = map.view();
    let off = |o: f64| DepthTest::Dual { offset: D24::plane_z(o) };
    let s = |test, z| shadow(&view, &cfg(test, Filter::Point), &at::<D24>(1.5, 1.5, z), &mut NoProbe);
    assert_eq!(s(DepthTest::First, 0.45), Shadow::ONE);
    assert_eq!(s(DepthTest::Second, 0.45), Shadow::ZERO);
    assert_eq!(s(DepthTest::Midpoint, 0.45), Shadow::ZERO);
    assert_eq!(s(DepthTest::Midpoint, 0.55), Shadow::ONE);
    assert_eq!(s(off(0.1), 0.45), Shadow::ONE);
    assert_eq!(s(off(0.2), 0.45), Shadow::ZERO);
    // Second depth: a point at exactly the stored z2 is lit (z ≤ z2), a
    // point one LSB farther is not.
    let on_z2 = PlaneZ::from_bits(D24::widen(D24::quantize(0.7)));
    let second = cfg(DepthTest::Second, Filter::Point);
    let at_depth = |z: PlaneZ| Lookup { z, ..at::<D24>(1.5, 1.5, 0.0) };
    assert_eq!(shadow(&view, &second, &at_depth(on_z2), &mut NoProbe), Shadow::ZERO);
    assert_eq!(shadow(&view, &second, &at_depth(on_z2 + PlaneZ::ONE), &mut NoProbe), Shadow::ONE);
    // A constant bias moves the comparison: 0.45 − 0.2 ≤ 0.3.
    let biased =
        ShadowConfig::new(DepthTest::First, Bias::Constant(D24::plane_z(0.2)), Filter::Point, false).expect("valid");
    assert_eq!(shadow(&view, &biased, &at::<D24>(1.5, 1.5, 0.45), &mut NoProbe), Shadow::ZERO);
}

/// One occluding texel of four: bilinear weights from the fractional
/// position, worked by hand.
#[test]
fn bilinear_weights() {
    let far = 1.0;
    let map = Map::<D16>::new(2, 2, &[0.2, far, far, far], &[]);
    let view = map.view();
    let f = cfg(DepthTest::First, Filter::Bilinear);
    let s = |x, y| shadow(&view, &f, &at::<D16>(x, y, 0.5), &mut NoProbe).to_num::<f64>();
    assert_eq!(s(1.0, 1.0), 0.25); // midway between the four centres
    assert_eq!(s(0.75, 1.0), 0.375); // (1 − 0.25)·(1 − 0.5)
    assert_eq!(s(0.5, 0.5), 1.0); // on the occluder's centre
    assert_eq!(s(1.5, 1.5), 0.0);
}

#[test]
fn outside_the_map_and_in_front_of_the_near_plane_is_lit() {
    let map = Map::<D16>::new(4, 4, &[0.1; 16], &[]);
    let view = map.view();
    for filter in [Filter::Point, Filter::Bilinear, Filter::Box { size: 3 }, Filter::Jittered(Jitter::REEVES)] {
        let c = cfg(DepthTest::First, filter);
        assert_eq!(shadow(&view, &c, &at::<D16>(-5.0, 1.0, 0.9), &mut NoProbe), Shadow::ZERO, "{filter:?}");
        assert_eq!(shadow(&view, &c, &at::<D16>(1.0, 9.0, 0.9), &mut NoProbe), Shadow::ZERO, "{filter:?}");
        assert_eq!(shadow(&view, &c, &at::<D16>(2.0, 2.0, -0.1), &mut NoProbe), Shadow::ZERO, "{filter:?}");
        assert_eq!(shadow(&view, &c, &at::<D16>(2.0, 2.0, 0.9), &mut NoProbe), Shadow::ONE, "{filter:?}");
    }
    // Half of a 4×4 box outside the map: those samples are lit.
    let c = cfg(DepthTest::First, Filter::Box { size: 4 });
    assert_eq!(shadow(&view, &c, &at::<D16>(0.0, 2.0, 0.9), &mut NoProbe).to_num::<f64>(), 0.5);
}

/// Reeves' Figure 4 sample counts, worked by hand.
#[test]
fn reeves_sample_grid() {
    let half = |v: f32| MapCoord::from_num(v);
    // 0.5 × 3 = 1.5 per side: 4 · 1.5 · 1.5 = 9 < 16, so ns = nt = round(3).
    assert_eq!(jitter_grid(&Jitter::REEVES, [half(0.5); 2]), ([half(1.5); 2], [3, 3]));
    // 12 × 3: nt = round(sqrt(3 · 16 / 12)) = 2, ns = round(16 / 2) = 8.
    assert_eq!(jitter_grid(&Jitter::REEVES, [half(4.0), half(1.0)]), ([half(12.0), half(3.0)], [8, 2]));
    // MinSize and MinSamples floor a point-sized footprint.
    let j = Jitter { min_size: half(2.0), min_samples: 2, ..Jitter::REEVES };
    assert_eq!(jitter_grid(&j, [MapCoord::ZERO; 2]), ([half(2.0); 2], [4, 4]));
    let one = Jitter { num_samples: 1, ..Jitter::REEVES };
    assert_eq!(jitter_grid(&one, [half(0.1); 2]).1, [1, 1]);
}

fn any_config() -> impl Strategy<Value = ShadowConfig> {
    let test = prop_oneof![
        Just(DepthTest::First),
        Just(DepthTest::Second),
        Just(DepthTest::Midpoint),
        (0.0f64..0.3).prop_map(|o| DepthTest::Dual { offset: D16::plane_z(o) }),
    ];
    let bias = prop_oneof![
        (0.0f64..0.05).prop_map(|b| Bias::Constant(D16::plane_z(b))),
        (0.0f64..0.02, 0.0f64..0.03).prop_map(|(a, b)| Bias::Range { lo: D16::plane_z(a), hi: D16::plane_z(a + b) }),
    ];
    let filter = prop_oneof![
        Just(Filter::Point),
        Just(Filter::Bilinear),
        (1u8..=5).prop_map(|size| Filter::Box { size }),
        (1u16..=32, 0.5f32..4.0, 1u16..=2, 0.0f32..2.0).prop_map(|(n, r, m, s)| Filter::Jittered(Jitter {
            num_samples: n,
            res_factor: MapCoord::from_num(r),
            min_samples: m.min(n),
            min_size: MapCoord::from_num(s),
        })),
    ];
    (test, bias, filter).prop_map(|(t, b, f)| ShadowConfig::new(t, b, f, false).expect("valid by construction"))
}

fn lookup() -> impl Strategy<Value = Lookup> {
    let slope = prop::option::of(
        (-(1i64 << 41)..(1i64 << 41), -(1i64 << 41)..(1i64 << 41)).prop_map(|(du, dv)| Slope { du, dv }),
    );
    (-4.0f32..52.0, -4.0f32..52.0, -0.1f32..1.1, [0.0f32..6.0, 0.0f32..6.0], any::<u64>(), slope).prop_map(
        |(x, y, z, f, seed, slope)| Lookup { footprint: f.map(MapCoord::from_num), seed, slope, ..at::<D16>(x, y, z) },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// On maps from the light pass: every filter returns a fraction in
    /// [0, 1], equal seeds give equal results, and culling lookups changes
    /// no verdict (while reading fewer texels).
    #[test]
    fn fractions_seeds_and_culled_lookups(
        tris in triangles(16),
        configs in prop::collection::vec(any_config(), 4),
        lookups in prop::collection::vec(lookup(), 24),
    ) {
        let (maps, _) = run::<D16, _, 16>(config(48, 8, DepthUnit::Dual, true), &tris, CullMode::None, 64, NoProbe);
        let raster = config(48, 8, DepthUnit::Dual, true).raster;
        let view = MapView::<D16>::new(raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
        let (mut culled, mut plain) = (Totals::default(), Totals::default());
        for c in &configs {
            let (with_culling, without) = (c.with_cull_lookups(true), c.with_cull_lookups(false));
            for l in &lookups {
                let s = shadow(&view, c, l, &mut NoProbe);
                prop_assert!(s <= Shadow::ONE);
                prop_assert_eq!(s, shadow(&view, c, l, &mut NoProbe), "same seed, same result");
                prop_assert_eq!(shadow(&view, &with_culling, l, &mut culled), shadow(&view, &without, l, &mut plain));
            }
        }
        prop_assert!(culled.map_reads() <= plain.map_reads());
        prop_assert!(plain.lookups_culled <= culled.lookups_culled, "culling off skips only lookups wholly outside the map");
    }
}

/// A map far behind every lookup is skipped wholesale: lit without a read.
#[test]
fn lookups_in_front_of_every_tile_read_nothing() {
    let map = Map::<D16>::new(16, 16, &[0.9; 256], &[0.95; 256]);
    let view = map.view();
    let c = ShadowConfig::new(DepthTest::Second, Bias::ZERO, Filter::Box { size: 3 }, true).expect("valid");
    let mut p = Totals::default();
    assert_eq!(shadow(&view, &c, &at::<D16>(8.0, 8.0, 0.5), &mut p), Shadow::ZERO);
    assert_eq!(shadow(&view, &c, &at::<D16>(8.0, 8.0, 0.99), &mut p), Shadow::ONE);
    assert_eq!((p.lookups_culled, p.map_reads()), (2, 0));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Any lookup bits at all: no panic, a fraction in [0, 1].
    #[test]
    fn arbitrary_lookups_never_panic(c in any_config(), x in any::<i32>(), y in any::<i32>(), z in any::<i64>(), f in [any::<i32>(), any::<i32>()], seed in any::<u64>()) {
        let map = Map::<D16>::new(16, 16, &[0.5; 256], &[0.6; 256]);
        let l = Lookup { x: MapCoord::from_bits(x), y: MapCoord::from_bits(y), z: PlaneZ::from_bits(z), footprint: f.map(MapCoord::from_bits), seed, slope: None };
        for culling in [false, true] {
            prop_assert!(shadow(&map.view(), &c.with_cull_lookups(culling), &l, &mut NoProbe) <= Shadow::ONE);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Forward differences are exact: one texel to the right adds exactly
    /// `du`, one down exactly `dv`, so stepping across a footprint gives the
    /// bits of direct evaluation at every texel centre.
    #[test]
    fn forward_differences_equal_direct_evaluation(
        x in -40.0f32..80.0, y in -40.0f32..80.0, z in 0.0f32..1.0,
        du in -(1i64 << 44)..(1i64 << 44), dv in -(1i64 << 44)..(1i64 << 44),
        x0 in -20i32..60, y0 in -20i32..60, n in 1i32..16,
    ) {
        let l = Lookup { slope: Some(Slope { du, dv }), ..at::<D24>(x, y, z) };
        for j in 0..n {
            let mut stepped = l.depth_at(x0, y0 + j);
            prop_assert_eq!(stepped, l.depth_at(x0, y0).saturating_add(dv * i64::from(j)));
            for i in 0..n {
                prop_assert_eq!(stepped, l.depth_at(x0 + i, y0 + j), "texel ({}, {})", x0 + i, y0 + j);
                stepped += du;
            }
        }
    }
}

/// A plane through the light's view direction has `C = 0`: no slope, and
/// the pixel keeps the ordinary verdict, reported as a fallback.
#[test]
fn grazing_tangent_planes_fall_back() {
    use umbra::core::glam::{Mat4, Vec3};
    let raster = RasterConfig::new(16, 16, 8, 8).expect("valid");
    // Orthographic light looking down −z: clip = (x, y, 1 − z, 1).
    let light = Mat4::from_cols_array_2d(&[
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0, 1.0],
    ]);
    let inv_t = light.inverse().transpose();
    let facing = TangentPlane::new(Vec3::new(0.0, 0.0, 0.5), Vec3::Z, &inv_t);
    assert_eq!(facing.slope::<D16>(&raster), Some(Slope { du: 0, dv: 0 }));
    let grazing = TangentPlane::new(Vec3::new(0.0, 0.0, 0.5), Vec3::X, &inv_t);
    assert_eq!(grazing.slope::<D16>(&raster), None);
    // Tilted by 45° about y: depth 1 − z changes by one NDC unit per NDC
    // unit of x, i.e. by 2/16 of the range per texel.
    let tilted = TangentPlane::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0).normalize(), &inv_t);
    let s = tilted.slope::<D16>(&raster).expect("steep but not grazing");
    assert_eq!(s.dv, 0);
    assert_eq!(s.du, ((65535i64 << 32) as f64 / 8.0).round() as i64);

    // A pixel whose ordinary samples disagree, with a grazing tangent plane.
    let map = Map::<D16>::new(16, 16, &(0..256).map(|i| if i % 2 == 0 { 0.2 } else { 0.8 }).collect::<Vec<_>>(), &[]);
    let c = cfg(DepthTest::First, Filter::Box { size: 3 });
    let mut events = Totals::default();
    let l = at::<D16>(8.0, 8.0, 0.5);
    let s = shadow_with_virtual_samples(&map.view(), &c, &l, || grazing.slope::<D16>(&raster), &mut events);
    assert_eq!(s, shadow(&map.view(), &c, &l, &mut NoProbe));
    assert_eq!(
        (events.tangent_setups, events.tangent_fallbacks, events.trivial_pixels(), events.virtual_samples),
        (1, 1, 0, 0)
    );
}

/// A tilted plane drawn twice (both windings) by the light pass: `z1` and
/// `z2` are both the plane, the case where the receiver is the stored
/// second surface. Points on the plane compared by the ordinary second-depth
/// test with a 3×3 box see half their neighbours nearer (acne); with
/// virtual samples each texel is compared with the plane at its own centre,
/// and only rounding ties can differ. The agreeing pixels are decided
/// without a tangent plane.
#[test]
fn virtual_samples_remove_self_shadowing_on_a_planar_receiver() {
    use umbra::core::glam::{Mat4, Vec3, Vec4};
    let size = 64u32;
    // Orthographic light: clip = (x, y, 0.5 − 0.3·x − 0.1·y, 1): a tilted plane z = 0 in world.
    let light = Mat4::from_cols_array_2d(&[
        [1.0, 0.0, -0.3, 0.0],
        [0.0, 1.0, -0.1, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.5, 1.0],
    ]);
    let quad =
        [Vec3::new(-2.0, -2.0, 0.0), Vec3::new(2.0, -2.0, 0.0), Vec3::new(2.0, 2.0, 0.0), Vec3::new(-2.0, 2.0, 0.0)];
    let clip = |p: Vec3| light * p.extend(1.0);
    let tris: Vec<[Vec4; 3]> =
        [[0, 1, 2], [0, 2, 3], [0, 2, 1], [0, 3, 2]].iter().map(|t: &[usize; 3]| t.map(|i| clip(quad[i]))).collect();
    let (maps, _) = run::<D16, _, 16>(config(size, 16, DepthUnit::Dual, false), &tris, CullMode::None, 64, NoProbe);
    let raster = config(size, 16, DepthUnit::Dual, false).raster;
    let view = MapView::<D16>::new(raster, &maps.z1, &maps.z2, &maps.tiles).expect("sized");
    let c = cfg(DepthTest::Second, Filter::Box { size: 3 });
    let inv_t = light.inverse().transpose();
    let (mut acne_plain, mut acne_virtual, mut events) = (0, 0, Totals::default());
    let n = 40;
    for k in 0..n * n {
        // World points spread over the middle of the plane, off texel centres.
        let p = Vec3::new(
            -1.5 + 3.0 * (k % n) as f32 / n as f32 + 0.013,
            -1.5 + 3.0 * (k / n) as f32 / n as f32 + 0.007,
            0.0,
        );
        let c4 = clip(p);
        let l = Lookup {
            x: MapCoord::from_num((f64::from(c4.x) + 1.0) * f64::from(size) / 2.0),
            y: MapCoord::from_num((1.0 - f64::from(c4.y)) * f64::from(size) / 2.0),
            z: D16::plane_z(f64::from(c4.z)),
            footprint: [MapCoord::ZERO; 2],
            seed: k as u64,
            slope: None,
        };
        acne_plain += u32::from(shadow(&view, &c, &l, &mut NoProbe) > Shadow::ZERO);
        let plane = TangentPlane::new(p, Vec3::Z, &inv_t);
        acne_virtual += u32::from(
            shadow_with_virtual_samples(&view, &c, &l, || plane.slope::<D16>(&raster), &mut events) > Shadow::ZERO,
        );
    }
    let total = (n * n) as u32;
    // Measured: 728 of 1600 (45 %) for this plane and grid.
    assert!(acne_plain > total / 3, "the ordinary test should self-shadow: {acne_plain} of {total}");
    // A rounding tie could flip a sample in principle; on this fixed grid none
    // does (measured: 0 of 1600, with 728 pixels needing a tangent plane).
    assert_eq!(acne_virtual, 0, "virtual samples: {acne_virtual} of {total} pixels shadowed");
    assert_eq!(events.tangent_setups + events.trivial_pixels(), u64::from(total));
    assert!(events.virtual_samples > 0);
}

/// Percentage-closer filtering written out by hand (Reeves et al. 1987 §2):
/// the `n × n` texel centres nearest the point, the receiver on its tangent
/// plane at each centre, less the bias, rounded half up to the format's
/// LSBs; a texel off the map is lit; the fraction rounded to 2⁻¹⁶.
#[allow(clippy::too_many_arguments, reason = "the lookup, spelled out")]
fn box_by_hand(
    w: u32,
    h: u32,
    scale: i64,
    z1: &[i64],
    z2: &[i64],
    test: DepthTest,
    bias: i64,
    n: i64,
    l: &Lookup,
) -> Shadow {
    if l.z.to_bits() < 0 {
        return Shadow::ZERO;
    }
    let first = |c: MapCoord| (i64::from(c.to_bits()) - (n - 1) * (1 << 15)).div_euclid(1 << 16);
    let (x0, y0) = (first(l.x), first(l.y));
    let (du, dv) = l.slope.map_or((0, 0), |s| (i128::from(s.du), i128::from(s.dv)));
    let mut shadowed = 0i64;
    for ty in y0..y0 + n {
        for tx in x0..x0 + n {
            if tx < 0 || ty < 0 || tx >= i64::from(w) || ty >= i64::from(h) {
                continue;
            }
            let centre = |t: i64, p: MapCoord| i128::from((t << 16) + (1 << 15) - i64::from(p.to_bits()));
            let receiver = i128::from(l.z.to_bits()) + ((du * centre(tx, l.x)) >> 16) + ((dv * centre(ty, l.y)) >> 16)
                - i128::from(bias);
            let lsb = ((receiver + (1 << 31)) >> 32).clamp(0, i128::from(scale));
            let i = usize::try_from(ty * i64::from(w) + tx).expect("on the map");
            let (a, b) = (i128::from(z1[i]) << 32, i128::from(z2[i]) << 32);
            let reference = match test {
                DepthTest::First => a,
                DepthTest::Second => b,
                DepthTest::Midpoint => (a + b) / 2,
                DepthTest::Dual { offset } => a + ((b - a) / 2).min(i128::from(offset.to_bits().max(0))),
            };
            shadowed += i64::from((lsb << 32) > reference);
        }
    }
    let all = n * n;
    Shadow::from_bits(u32::try_from((2 * shadowed * 65_536 + all) / (2 * all)).expect("at most one"))
}

/// Depths on a few levels, so that receivers meet stored surfaces exactly.
fn levels(texels: usize) -> impl Strategy<Value = (Vec<f32>, Vec<f32>)> {
    let level = prop::sample::select(vec![0.2f32, 0.35, 0.5, 0.65, 0.8, 1.0]);
    prop::collection::vec((level.clone(), level), texels)
        .prop_map(|p| p.into_iter().map(|(a, b)| (a.min(b), a.max(b))).unzip())
}

fn box_against_hand<F: DepthFormat>(
    (z1, z2): &(Vec<f32>, Vec<f32>),
    test: DepthTest,
    bias: f64,
    n: u8,
    lookups: &[Lookup],
) -> Result<(), TestCaseError>
where
    F::Texel: Into<i64>,
{
    let (w, h) = (20, 12);
    let map = Map::<F>::new(w, h, z1, z2);
    let texels = |b: &[F::Texel]| b.iter().map(|&t| t.into()).collect::<Vec<i64>>();
    let (t1, t2) = (texels(&map.z1), texels(&map.z2));
    let b = F::plane_z(bias);
    for l in lookups {
        let expected = box_by_hand(w, h, F::SCALE, &t1, &t2, test, b.to_bits(), i64::from(n), l);
        for culling in [false, true] {
            let c = ShadowConfig::new(test, Bias::Constant(b), Filter::Box { size: n }, culling).expect("valid");
            prop_assert_eq!(shadow(&map.view(), &c, l, &mut NoProbe), expected, "{:?}, culling {}", l, culling);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Every box size, depth test and format, on and off the map (tiles
    /// cut by its edge), with and without a tangent plane and with culling
    /// on and off: the box filter counts what the hand-written filter counts.
    #[test]
    fn box_filters_count_what_a_hand_count_does(
        depths in levels(240),
        test in prop_oneof![
            Just(DepthTest::First),
            Just(DepthTest::Second),
            Just(DepthTest::Midpoint),
            (0.0f64..0.3).prop_map(|o| DepthTest::Dual { offset: D24::plane_z(o) }),
        ],
        bias in prop_oneof![Just(0.0f64), 0.0f64..0.05],
        n in 1u8..=16,
        points in prop::collection::vec(
            (
                -6.0f32..26.0,
                -6.0f32..18.0,
                prop_oneof![prop::sample::select(vec![0.2f32, 0.35, 0.5, 0.65, 0.8, 1.0]), -0.05f32..1.05],
                prop::option::of((-(1i64 << 36)..(1i64 << 36), -(1i64 << 36)..(1i64 << 36))),
            ),
            16,
        ),
    ) {
        let lookups = |f: fn(f32, f32, f32) -> Lookup| -> Vec<Lookup> {
            points
                .iter()
                .map(|&(x, y, z, s)| Lookup { slope: s.map(|(du, dv)| Slope { du, dv }), ..f(x, y, z) })
                .collect()
        };
        box_against_hand::<D16>(&depths, test, bias, n, &lookups(at::<D16>))?;
        box_against_hand::<D24>(&depths, test, bias, n, &lookups(at::<D24>))?;
    }
}
