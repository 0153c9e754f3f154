//! A light pass built with one datapath ([`Datapaths`]) makes the maps, the
//! ids, the tile summaries and the events of a pass built with every
//! datapath, and refuses a configuration it was not built for.

use proptest::prelude::*;
use umbra::core::glam::Vec4;
use umbra::core::probe::Totals;
use umbra::core::{
    ConfigError, CullMode, D16, D24, Datapaths, DepthFormat, DepthUnit, DualOnly, Every, SingleOnly, VisibilityOnly,
};

use crate::common::{Buffers, config, triangles};

const SIZE: u32 = 64;

/// Draw `tris` through a pass built with `D`: the buffers and the totals.
fn draw<F: DepthFormat, D: Datapaths>(
    tris: &[[Vec4; 3]],
    unit: DepthUnit,
    ids: bool,
    cull: bool,
    tile: u32,
) -> (Buffers<F, 4>, Totals) {
    let cfg = config(SIZE, tile, unit, cull);
    // A small store and bins, so that tiles are flushed, loaded back and
    // their max goes stale between draws.
    let mut b = Buffers::<F, 4>::new(&cfg, 8, ids);
    let mut pass = b.pass_built::<Totals, D>(cfg, Totals::default()).expect("built for this configuration");
    for t in tris {
        pass.draw_clip(*t, CullMode::None);
    }
    let totals = pass.finish();
    (b, totals)
}

/// Both builds, everything compared.
fn same<F: DepthFormat, D: Datapaths>(
    tris: &[[Vec4; 3]],
    unit: DepthUnit,
    ids: bool,
    cull: bool,
    tile: u32,
) -> Result<(), TestCaseError> {
    let (every, every_totals) = draw::<F, Every>(tris, unit, ids, cull, tile);
    let (one, one_totals) = draw::<F, D>(tris, unit, ids, cull, tile);
    prop_assert!(every.z1 == one.z1, "z1 differs ({unit:?}, ids {ids}, cull {cull})");
    prop_assert!(every.z2 == one.z2, "z2 differs ({unit:?}, cull {cull})");
    prop_assert_eq!(&every.ids, &one.ids);
    // The summaries whole: bounds, the max and how many texels hold it.
    prop_assert_eq!(&every.tiles, &one.tiles);
    prop_assert_eq!(every_totals, one_totals);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn one_datapath_builds_make_the_same_bits(tris in triangles(48), tile in prop::sample::select(vec![8u32, 16])) {
        same::<D16, DualOnly<true>>(&tris, DepthUnit::Dual, false, true, tile)?;
        same::<D16, DualOnly<false>>(&tris, DepthUnit::Dual, false, false, tile)?;
        same::<D24, SingleOnly<true>>(&tris, DepthUnit::Single, false, true, tile)?;
        same::<D24, SingleOnly<false>>(&tris, DepthUnit::Single, false, false, tile)?;
        same::<D24, VisibilityOnly<true>>(&tris, DepthUnit::Single, true, true, tile)?;
        same::<D16, VisibilityOnly<false>>(&tris, DepthUnit::Single, true, false, tile)?;
    }
}

#[test]
fn a_pass_refuses_a_configuration_it_was_not_built_for() {
    let refused = |unit: DepthUnit, ids: bool, cull: bool, r: Result<(), ConfigError>| {
        assert_eq!(r, Err(ConfigError::NotBuilt { unit, ids, max_z_cull: cull }), "{unit:?} ids {ids} cull {cull}");
    };
    let start = |unit: DepthUnit, ids: bool, cull: bool| {
        let cfg = config(SIZE, 16, unit, cull);
        let mut b = Buffers::<D16, 4>::new(&cfg, 8, ids);
        [
            b.pass_built::<Totals, DualOnly<true>>(cfg, Totals::default()).map(drop),
            b.pass_built::<Totals, SingleOnly<true>>(cfg, Totals::default()).map(drop),
            b.pass_built::<Totals, VisibilityOnly<false>>(cfg, Totals::default()).map(drop),
        ]
    };
    let [dual, single, visibility] = start(DepthUnit::Dual, false, true);
    assert_eq!(dual, Ok(()));
    refused(DepthUnit::Dual, false, true, single);
    refused(DepthUnit::Dual, false, true, visibility);
    let [dual, single, visibility] = start(DepthUnit::Single, false, false);
    refused(DepthUnit::Single, false, false, dual);
    refused(DepthUnit::Single, false, false, single);
    refused(DepthUnit::Single, false, false, visibility);
    let [dual, single, visibility] = start(DepthUnit::Single, true, false);
    refused(DepthUnit::Single, true, false, dual);
    refused(DepthUnit::Single, true, false, single);
    assert_eq!(visibility, Ok(()));
    let message = ConfigError::NotBuilt { unit: DepthUnit::Single, ids: true, max_z_cull: false }.to_string();
    assert_eq!(
        message,
        "this light pass is not built with the Single depth unit with triangle ids without max-z culling"
    );
}
