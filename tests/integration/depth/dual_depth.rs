//! The dual depth unit keeps the two smallest fragment depths per texel,
//! and the units' results do not depend on triangle order.

use proptest::prelude::*;
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthUnit, NoProbe};

use crate::common::{Recorder, config, raw, run, triangles, two_smallest};

const SIZE: u32 = 48;

fn check_two_smallest<F: DepthFormat>(tris: &[[umbra::core::glam::Vec4; 3]]) -> Result<(), TestCaseError> {
    let cfg = config(SIZE, 16, DepthUnit::Dual, false);
    let (maps, rec) = run::<F, _, 64>(cfg, tris, CullMode::None, 4096, Recorder::default());
    let far = umbra::core::depth::Texel::to_raw(F::FAR);
    let (want1, want2) = two_smallest(&rec.fragments, SIZE, far);
    let (z1, z2) = (raw(&maps.z1), raw(&maps.z2));
    for i in 0..z1.len() {
        prop_assert!(z1[i] <= z2[i], "z1 > z2 at texel {}", i);
        prop_assert_eq!((z1[i], z2[i]), (want1[i], want2[i]), "texel {}", i);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn dual_holds_the_two_smallest_fragment_depths_d16(tris in triangles(24)) {
        check_two_smallest::<D16>(&tris)?;
    }

    #[test]
    fn dual_holds_the_two_smallest_fragment_depths_d24(tris in triangles(24)) {
        check_two_smallest::<D24>(&tris)?;
    }

    #[test]
    fn single_and_dual_do_not_depend_on_triangle_order(
        (tris, shuffled) in triangles(16).prop_flat_map(|t| (Just(t.clone()), Just(t).prop_shuffle()))
    ) {
        let single = config(SIZE, 8, DepthUnit::Single, true);
        let dual = config(SIZE, 8, DepthUnit::Dual, true);
        let (s1, _) = run::<D24, _, 4>(single, &tris, CullMode::None, 64, NoProbe);
        let (s2, _) = run::<D24, _, 4>(single, &shuffled, CullMode::None, 64, NoProbe);
        let (d1, _) = run::<D24, _, 4>(dual, &tris, CullMode::None, 64, NoProbe);
        let (d2, _) = run::<D24, _, 4>(dual, &shuffled, CullMode::None, 64, NoProbe);
        prop_assert_eq!(&s1.z1, &s2.z1, "single depends on order");
        prop_assert_eq!(&d1.z1, &d2.z1, "dual z1 depends on order");
        prop_assert_eq!(&d1.z2, &d2.z2, "dual z2 depends on order");
        prop_assert_eq!(&s1.z1, &d1.z1, "single z1 differs from dual z1");
    }
}

/// Second depth by front-face culling on a closed box seen from the light:
/// the map holds the box's far side, as Wang & Molnar's single-buffer
/// variant prescribes, and the dual unit's `z2` agrees with it.
#[test]
fn front_face_culling_gives_the_far_side_of_a_solid() {
    use umbra::core::glam::Vec3;
    use umbra::sim::world::mesh::Mesh;
    let cube = Mesh::cuboid(Vec3::new(-0.5, -0.5, 0.2), Vec3::new(0.5, 0.5, 0.6));
    // An orthographic light on +z looking down −z: clip = (x, y, 1 − z, 1),
    // so the +z face (z = 0.6) is nearest with depth 0.4 and faces the light.
    let m = umbra::core::glam::Mat4::from_cols_array_2d(&[
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0, 1.0],
    ]);
    let tris: Vec<[umbra::core::glam::Vec4; 3]> =
        cube.triangles.iter().map(|t| t.map(|i| m * cube.positions[i as usize].extend(1.0))).collect();
    let (front, _) = run::<D16, _, 64>(config(32, 8, DepthUnit::Single, true), &tris, CullMode::Front, 64, NoProbe);
    let (back, _) = run::<D16, _, 64>(config(32, 8, DepthUnit::Single, true), &tris, CullMode::Back, 64, NoProbe);
    let (dual, _) = run::<D16, _, 64>(config(32, 8, DepthUnit::Dual, true), &tris, CullMode::None, 64, NoProbe);
    // The centre texel: nearest is the top face at 1 − 0.6, second the bottom at 1 − 0.2.
    let centre = (16 * 32 + 16) as usize;
    assert_eq!(back.z1[centre], D16::quantize(0.4));
    assert_eq!(front.z1[centre], D16::quantize(0.8));
    assert_eq!(dual.z1[centre], D16::quantize(0.4));
    // Top and bottom faces cover the same texels, the sides are edge-on: the
    // dual unit's two buffers are exactly the back- and front-culled maps.
    assert_eq!(dual.z1, back.z1);
    assert_eq!(dual.z2, front.z1);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// The visibility unit keeps, per pixel, the id of the nearest fragment
    /// (the first drawn among equals), checked against every recorded
    /// fragment; its depths are the single unit's; with culling or without.
    #[test]
    fn visibility_ids_are_the_nearest_fragments(tris in triangles(24), cull in any::<bool>(), tile in prop::sample::select(vec![8u32, 16, 64])) {
        use crate::common::run_visibility;
        use umbra::core::NO_TRIANGLE;
        let (ids, z1, _) = run_visibility::<D24>(SIZE, tile, &tris, cull);
        let (_, rec) = run::<D24, _, 64>(config(SIZE, 16, DepthUnit::Single, false), &tris, CullMode::None, 4096, Recorder::default());
        let (single, _) = run::<D24, _, 64>(config(SIZE, 16, DepthUnit::Single, false), &tris, CullMode::None, 4096, NoProbe);
        prop_assert_eq!(&z1, &single.z1);
        let mut best: Vec<Option<(u32, u32)>> = vec![None; (SIZE * SIZE) as usize];
        for f in &rec.fragments {
            let b = &mut best[(f.y * SIZE + f.x) as usize];
            if b.is_none_or(|(d, t)| (f.depth, f.triangle) < (d, t)) {
                *b = Some((f.depth, f.triangle));
            }
        }
        for (i, b) in best.iter().enumerate() {
            prop_assert_eq!(ids[i], b.map_or(NO_TRIANGLE, |(_, t)| t), "pixel {}", i);
        }
    }
}
