//! Per-tile max-z culling never changes the maps, it does skip work where
//! it can, and the per-tile summaries are exact.

use proptest::prelude::*;
use umbra::core::glam::Vec4;
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthUnit, F32, NoProbe};

use crate::common::{Recorder, config, raw, run, triangles};

const SIZE: u32 = 64;

fn culling_changes_nothing<F: DepthFormat>(
    tris: &[[Vec4; 3]],
    unit: DepthUnit,
    tile: u32,
) -> Result<(), TestCaseError> {
    let (on, _) = run::<F, _, 8>(config(SIZE, tile, unit, true), tris, CullMode::None, 32, NoProbe);
    let (off, _) = run::<F, _, 8>(config(SIZE, tile, unit, false), tris, CullMode::None, 32, NoProbe);
    prop_assert_eq!(raw(&on.z1), raw(&off.z1));
    prop_assert_eq!(raw(&on.z2), raw(&off.z2));
    // The summaries: the exact min and max of each tile's texels.
    let r = config(SIZE, tile, unit, true).raster;
    for (i, st) in on.tiles.iter().enumerate() {
        let rect = r.tile_rect(r.tile_id(i));
        let texels = |buf: &[F::Texel]| -> Vec<u32> {
            (rect.y0..rect.y1)
                .flat_map(|y| (rect.x0..rect.x1).map(move |x| (y * SIZE + x) as usize))
                .map(|k| raw(&buf[k..=k])[0])
                .collect()
        };
        let z1 = texels(&on.z1);
        let lo_hi = |v: &[u32]| (v.iter().copied().min().unwrap_or(0), v.iter().copied().max().unwrap_or(0));
        prop_assert_eq!((raw(&[st.z1_min])[0], raw(&[st.z1_max])[0]), lo_hi(&z1), "tile {} z1 bounds", i);
        let culled = if unit == DepthUnit::Dual { texels(&on.z2) } else { z1 };
        prop_assert_eq!(raw(&[st.cull_max()])[0], lo_hi(&culled).1, "tile {} max", i);
        if unit == DepthUnit::Dual {
            let z2 = texels(&on.z2);
            prop_assert_eq!((raw(&[st.z2_min])[0], raw(&[st.z2_max])[0]), lo_hi(&z2), "tile {} z2 bounds", i);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn max_z_culling_never_changes_the_maps(tris in triangles(40), tile in prop::sample::select(vec![8u32, 16, 32, 64])) {
        culling_changes_nothing::<D16>(&tris, DepthUnit::Single, tile)?;
        culling_changes_nothing::<D24>(&tris, DepthUnit::Dual, tile)?;
        culling_changes_nothing::<F32>(&tris, DepthUnit::Dual, tile)?;
    }
}

/// Screen-filling quads at depths `zs`, in that order.
fn layers(zs: &[f32]) -> Vec<[Vec4; 3]> {
    zs.iter()
        .flat_map(|&z| {
            let v = |x: f32, y: f32| Vec4::new(x, y, z, 1.0);
            [[v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0)], [v(-1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)]]
        })
        .collect()
}

#[test]
fn front_to_back_layers_are_culled_and_back_to_front_are_not() {
    let front_to_back: Vec<f32> = (0..8).map(|i| 0.1 + 0.1 * i as f32).collect();
    let back_to_front: Vec<f32> = front_to_back.iter().rev().copied().collect();
    for unit in [DepthUnit::Single, DepthUnit::Dual] {
        let kept = if unit == DepthUnit::Dual { 2 } else { 1 };
        let pass = |zs: &[f32]| {
            run::<D24, _, 64>(config(SIZE, 16, unit, true), &layers(zs), CullMode::None, 64, Recorder::default()).1
        };
        let (ftb, btf) = (pass(&front_to_back), pass(&back_to_front));
        // Front to back, only the first `kept` layers reach the depth unit:
        // every later triangle lies behind its tile's max. A layer's two
        // triangles share the diagonal, which crosses the 4 diagonal tiles
        // of the 4×4 grid; each of the other 12 tiles meets one triangle:
        // 4·2 + 12·1 = 20 triangle-in-tile pairs per culled layer.
        assert_eq!(ftb.fragment_events, kept * u64::from(SIZE * SIZE), "{unit:?}");
        assert_eq!(ftb.culled, (8 - kept as u32) * 20, "{unit:?}");
        // Back to front, every layer is nearer than the tile: nothing culled.
        assert_eq!(btf.culled, 0, "{unit:?}");
        assert_eq!(btf.fragment_events, 8 * u64::from(SIZE * SIZE), "{unit:?}");
    }
}
