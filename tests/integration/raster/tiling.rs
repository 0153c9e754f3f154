//! The tiled rasterizer emits exactly the fragments of the plain
//! whole-target reference, for every tile size, bin capacity and setup
//! store size — including ones small enough to force early flushes — and
//! an unwatched pass (whose depth unit takes runs of covered pixels as
//! spans) draws the maps those fragments make.

use proptest::prelude::*;
use umbra::core::glam::Vec4;
use umbra::core::probe::Fragment;
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthUnit, F32, NoProbe};

use crate::common::{Recorder, assert_matches_reference, config, raw, reference, run, triangles, two_smallest};

const SIZE: u32 = 64;

fn fragments<F: DepthFormat, const B: usize>(
    tris: &[[Vec4; 3]],
    tile: u32,
    setups: usize,
    cull: CullMode,
) -> (Vec<Fragment>, Recorder) {
    let (_, rec) = run::<F, _, B>(config(SIZE, tile, DepthUnit::Dual, false), tris, cull, setups, Recorder::default());
    let counts = rec.clone();
    (rec.sorted(), counts)
}

/// The dual maps of a pass that reports nothing.
fn unwatched<F: DepthFormat, const B: usize>(
    tris: &[[Vec4; 3]],
    tile: u32,
    setups: usize,
    cull: CullMode,
) -> (Vec<u32>, Vec<u32>) {
    let (maps, _) = run::<F, _, B>(config(SIZE, tile, DepthUnit::Dual, false), tris, cull, setups, NoProbe);
    (raw(&maps.z1), raw(&maps.z2))
}

fn every_tiling_agrees<F: DepthFormat>(tris: &[[Vec4; 3]], cull: CullMode) -> Result<Vec<Fragment>, TestCaseError> {
    let (base, _) = fragments::<F, 64>(tris, 128, 4096, cull);
    let maps = two_smallest(&base, SIZE, umbra::core::depth::Texel::to_raw(F::FAR));
    for tile in [8, 16, 32, 64] {
        prop_assert_eq!(&fragments::<F, 64>(tris, tile, 4096, cull).0, &base, "tile {}", tile);
    }
    for tile in [8, 16, 32, 64, 128] {
        prop_assert!(unwatched::<F, 64>(tris, tile, 4096, cull) == maps, "maps with tile {}", tile);
    }
    prop_assert_eq!(&fragments::<F, 1>(tris, 8, 4096, cull).0, &base, "bin capacity 1");
    prop_assert_eq!(&fragments::<F, 2>(tris, 16, 3, cull).0, &base, "bin capacity 2, 3 setups");
    prop_assert_eq!(&fragments::<F, 3>(tris, 32, 1, cull).0, &base, "bin capacity 3, 1 setup");
    prop_assert!(unwatched::<F, 3>(tris, 32, 1, cull) == maps, "maps with bin capacity 3, 1 setup");
    Ok(base)
}

/// A triangle with one vertex near the target and two up to 600 targets'
/// half-widths away (at most 2¹⁷ pixels from it: inside the guard band).
fn vast_triangle() -> impl Strategy<Value = [Vec4; 3]> {
    let far = || (-600.0f32..600.0, -600.0f32..600.0).prop_map(|(x, y)| Vec4::new(x, y, 0.5, 1.0));
    (-1.0f32..1.0, -1.0f32..1.0, far(), far()).prop_map(|(x, y, b, c)| [Vec4::new(x, y, 0.25, 1.0), b, c])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn tiled_fragments_equal_the_reference_d16(tris in triangles(12)) {
        let got = every_tiling_agrees::<D16>(&tris, CullMode::None)?;
        assert_matches_reference(got, reference::<D16>(SIZE, &tris, CullMode::None))?;
    }

    #[test]
    fn tiled_fragments_equal_the_reference_d24_with_culling(tris in triangles(12), back in any::<bool>()) {
        let cull = if back { CullMode::Back } else { CullMode::Front };
        let got = every_tiling_agrees::<D24>(&tris, cull)?;
        assert_matches_reference(got, reference::<D24>(SIZE, &tris, cull))?;
    }

    /// Triangles hundreds of targets across, inside the guard band: their
    /// edges cross the target with steps and values too large for the
    /// coverage-mask unit's 32-bit lanes, so small rectangles take its
    /// 64-bit serial unit — and thin ones crossing it take the lanes.
    #[test]
    fn vast_triangles_fragments_equal_the_reference(tris in prop::collection::vec(vast_triangle(), 1..6)) {
        let got = every_tiling_agrees::<D24>(&tris, CullMode::None)?;
        assert_matches_reference(got, reference::<D24>(SIZE, &tris, CullMode::None))?;
    }

    #[test]
    fn f32_fragments_do_not_depend_on_tiling(tris in triangles(12)) {
        every_tiling_agrees::<F32>(&tris, CullMode::None)?;
    }
}

/// Many triangles over one tile with bins of one entry: the bin flushes
/// early again and again, and the result is unchanged.
#[test]
fn full_bins_flush_early_and_change_nothing() {
    let quad = |z: f32| {
        let v = |x: f32, y: f32| Vec4::new(x, y, z, 1.0);
        [[v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0)], [v(-1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)]]
    };
    let tris: Vec<[Vec4; 3]> = (0..6).flat_map(|i| quad(0.9 - 0.1 * i as f32)).collect();
    let (small, rec_small) = fragments::<D24, 1>(&tris, 32, 5, CullMode::None);
    let (large, rec_large) = fragments::<D24, 64>(&tris, 32, 4096, CullMode::None);
    assert_eq!(small, large);
    // 12 triangles, two per quad; a quad's diagonal crosses the two
    // off-diagonal tiles, so those bin every triangle and the other two bin
    // every other one. The 5-entry setup store drains every bin after
    // triangles 5 and 10 (4 tiles each: 8 flushes); in between, a bin of one
    // entry flushes whenever a second triangle arrives: groups of 5, 5 and 2
    // triangles give 4+4+2+1, 4+4+1+2 and 1+1+0+0 = 24 early flushes.
    assert_eq!(rec_small.bin_full_flushes, 24);
    assert_eq!(rec_small.setup_full_flushes, 8);
    assert_eq!(rec_large.bin_full_flushes, 0);
    assert_eq!(small.len(), 12 * (SIZE * SIZE) as usize / 2);
}

fn mesh_fragments(
    positions: &[umbra::core::glam::Vec3],
    tris: &[[u32; 3]],
    m: &umbra::core::glam::Mat4,
) -> Vec<Fragment> {
    let cfg = config(SIZE, 16, DepthUnit::Dual, false);
    let mut b = crate::common::Buffers::<D24, 8>::new(&cfg, 64, false);
    let mut pass = b.pass(cfg, Recorder::default());
    pass.draw_mesh(positions, tris, m, CullMode::None).expect("valid indices");
    pass.finish().sorted()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Indexed meshes (through the post-transform cache, with indices that
    /// collide in it, and vertices in front of the near plane and beyond the
    /// far plane, so some triangles are clipped) give exactly the
    /// fragments of the same triangles submitted one by one in clip space.
    #[test]
    fn indexed_meshes_equal_triangle_soup(
        positions in prop::collection::vec((-2.0f32..2.0, -2.0f32..2.0, -4.0f32..2.8), 3..80),
        picks in prop::collection::vec(prop::array::uniform3(any::<prop::sample::Index>()), 1..40),
    ) {
        use umbra::core::glam::{Mat4, Vec3};
        let positions: Vec<Vec3> = positions.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
        let tris: Vec<[u32; 3]> = picks.iter().map(|t| t.map(|i| i.index(positions.len()) as u32)).collect();
        let view = umbra::core::glam::camera::rh::view::look_at_mat4(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y);
        let proj = umbra::core::glam::camera::rh::proj::directx::perspective(1.2, 1.0, 1.0, 6.0);
        let m: Mat4 = proj * view;
        let soup: Vec<[Vec4; 3]> = tris.iter().map(|t| t.map(|i| m * positions[i as usize].extend(1.0))).collect();
        let (_, rec) = run::<D24, _, 8>(config(SIZE, 16, DepthUnit::Dual, false), &soup, CullMode::None, 64, Recorder::default());
        prop_assert_eq!(mesh_fragments(&positions, &tris, &m), rec.sorted());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Slivers: two vertices a few subpixels apart with very different
    /// depths and a third far away, so the depth plane is steep enough that
    /// setup takes the exact i128 path; fragments still equal the reference.
    #[test]
    fn steep_slivers_equal_the_reference(
        a in (-1.0f32..1.0, -1.0f32..1.0),
        far in (-1.0f32..1.0, -1.0f32..1.0),
        nudge in (1i32..4, -3i32..4),
        z in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0),
    ) {
        let sub = 2.0 / (SIZE as f32 * 256.0);
        let tri = [
            Vec4::new(a.0, a.1, z.0, 1.0),
            Vec4::new(a.0 + nudge.0 as f32 * sub, a.1 + nudge.1 as f32 * sub, z.1, 1.0),
            Vec4::new(far.0, far.1, z.2, 1.0),
        ];
        let got = every_tiling_agrees::<D24>(&[tri], CullMode::None)?;
        assert_matches_reference(got, reference::<D24>(SIZE, &[tri], CullMode::None))?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A setup moved into a window ([`Setup::in_window`]: integer re-basing
    /// of edges and plane) equals the setup made from the vertices snapped
    /// in that window, and is `None` when the window's own setup finds no
    /// pixel to cover (or covers none of the window's pixel centres, when
    /// the window's front end rejects a small triangle that covers none).
    #[test]
    fn setups_moved_into_a_window_equal_setups_made_there(
        tris in triangles(12),
        (wx, wy) in (0u32..4, 0u32..4),
        (ww, wh) in (1u32..4, 1u32..4),
    ) {
        use umbra::core::RasterConfig;
        use umbra::core::front::{self, Output};
        use umbra::core::front::setup::Setup;
        let whole = RasterConfig::new(128, 128, 16, 8).expect("valid");
        let (x0, y0) = (wx * 32, wy * 32);
        let window = whole.window(x0, y0, (ww * 32).min(128 - x0), (wh * 32).min(128 - y0)).expect("window");
        // Each output, with the setup when there is one.
        let pieces = |raster: &RasterConfig, t: &[Vec4; 3]| {
            let mut out = Vec::new();
            front::clip::<D24>(raster, &t.map(|v| v.to_array().map(f64::from)), CullMode::None, 7, &mut |o| {
                out.push(match o { Output::Setup(s) => Some(*s), _ => None });
            });
            out
        };
        for t in &tris {
            let there = pieces(&window, t);
            let moved: Vec<Option<Setup>> =
                pieces(&whole, t).into_iter().map(|o| o.and_then(|s| s.in_window([x0, y0], &window))).collect();
            prop_assert_eq!(there.len(), moved.len());
            for (a, b) in there.iter().zip(&moved) {
                match (a, b) {
                    (Some(a), Some(b)) => prop_assert_eq!(a, b),
                    (Some(a), None) => prop_assert!(false, "the window covers {:?}, the moved setup nothing", a.bbox),
                    // The window's front end rejects a small triangle that
                    // covers none of its pixel centres before solving its
                    // plane; moved in, the same triangle covers none either.
                    (_, Some(b)) => {
                        let r = b.bbox;
                        let covered = (r.y0..r.y1)
                            .any(|y| (r.x0..r.x1).any(|x| b.covers(i64::from(x), i64::from(y))));
                        prop_assert!(!covered, "the moved setup covers pixels of {:?}, the window nothing", r);
                    }
                    (_, None) => {}
                }
            }
        }
    }
}
