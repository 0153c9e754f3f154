//! Every unit that sets up, rasterizes, reads or writes reports it: each
//! unit's event totals against the work the brute-force reference
//! rasterizer (or the filter's footprint, worked by hand) says it did.

use proptest::prelude::*;
use umbra::core::glam::Vec4;
use umbra::core::probe::Totals;
use umbra::core::shadow::{Bias, DepthTest, Filter, Lookup, MapCoord, MapView, ShadowConfig, shadow};
use umbra::core::stencil::StencilPass;
use umbra::core::{CullMode, D24, DepthFormat, DepthUnit, RasterConfig};

use crate::common::{config, horizontal_silhouette_edge, reference, run, triangles};

const SIZE: u32 = 64;
/// Bytes of a 24-bit texel.
const BYTES: u64 = 3;

/// Triangles the reference gives at least one fragment.
fn covering(tris: &[[Vec4; 3]]) -> u64 {
    let mut ids: Vec<u32> = reference::<D24>(SIZE, tris, CullMode::None).iter().map(|f| f.triangle).collect();
    ids.sort_unstable();
    ids.dedup();
    ids.len() as u64
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The front end, the raster and the dual depth unit: every submitted
    /// triangle is set up or rejected (these need no clipping), every one
    /// that covers a pixel centre was set up, the fragments are the
    /// reference's, the dual unit reads both buffers for each of them, and
    /// every bin entry is drained.
    #[test]
    fn the_light_pass_reports_its_work(tris in triangles(12)) {
        let cfg = config(SIZE, 16, DepthUnit::Dual, false);
        let (_, t) = run::<D24, _, 4>(cfg, &tris, CullMode::None, 64, Totals::default());
        let want = reference::<D24>(SIZE, &tris, CullMode::None).len() as u64;
        prop_assert_eq!(t.submitted, tris.len() as u64);
        prop_assert_eq!(t.setups + t.rejected(), t.submitted);
        prop_assert!(t.setups >= covering(&tris), "{} setups, {} covering", t.setups, covering(&tris));
        prop_assert_eq!(t.fragments, want);
        prop_assert_eq!((t.depth_reads_z1, t.depth_reads_z2), (want, want));
        prop_assert_eq!(t.depth_read_bytes, 2 * BYTES * want);
        prop_assert_eq!(t.flushed_triangles, t.bin_entries);
        prop_assert!(t.tile_stores + t.tile_clears >= u64::from((SIZE / 16) * (SIZE / 16)), "every tile stored");
    }

    /// The stencil unit: the same triangles as shadow-volume triangles over
    /// a scene depth of 0 (every fragment at or behind it). Each is set up
    /// or rejected, each fragment reads the scene depth and the stencil and
    /// writes the stencil.
    #[test]
    fn the_stencil_unit_reports_its_work(tris in triangles(12)) {
        let raster = RasterConfig::new(SIZE, SIZE, 16, 8).expect("valid");
        let n = raster.texel_count();
        let (depth, mut stencil) = (vec![0u32; n], vec![0u8; n]);
        let mut pass = StencilPass::<D24>::new(raster, &depth, &mut stencil).expect("sized");
        let mut t = Totals::default();
        for tri in &tris {
            pass.draw(&tri.map(|v| v.to_array().map(f64::from)), &mut t);
        }
        let want = reference::<D24>(SIZE, &tris, CullMode::None).len() as u64;
        prop_assert_eq!(t.submitted, tris.len() as u64);
        prop_assert_eq!(t.setups + t.rejected(), t.submitted);
        prop_assert!(t.setups >= covering(&tris), "{} setups, {} covering", t.setups, covering(&tris));
        prop_assert_eq!((t.volume_fragments, t.volume_depth_bytes), (want, BYTES * want));
        prop_assert_eq!((t.stencil_reads, t.stencil_writes), (want, want));
        prop_assert_eq!((t.stencil_read_bytes, t.stencil_write_bytes), (want, want));
    }

    /// The shadow unit: an `n × n` box at a texel centre inside the map, with
    /// lookup culling off, reads the `n²` texels of its footprint from each
    /// buffer its test compares (`z1`; `z1` and `z2` for the midpoint).
    #[test]
    fn the_shadow_unit_reports_its_reads(
        (i, j) in (8u32..56, 8u32..56),
        n in prop::sample::select(vec![1u8, 3, 5, 7]),
        midpoint in any::<bool>(),
        z in 0.0f32..1.0,
    ) {
        let raster = RasterConfig::new(SIZE, SIZE, 16, 8).expect("valid");
        let cleared = umbra::core::TileState::cleared(D24::FAR, 256);
        let (z1, z2, tiles) = (vec![D24::quantize(0.5); 4096], vec![D24::quantize(0.6); 4096], vec![cleared; 16]);
        let view = MapView::<D24>::new(raster, &z1, &z2, &tiles).expect("sized");
        let test = if midpoint { DepthTest::Midpoint } else { DepthTest::First };
        let cfg = ShadowConfig::new(test, Bias::ZERO, Filter::Box { size: n }, false).expect("valid");
        let centre = |c: u32| MapCoord::from_num(c) + MapCoord::from_num(0.5);
        let lookup = Lookup {
            x: centre(i),
            y: centre(j),
            z: D24::plane_z(f64::from(z)),
            footprint: [MapCoord::ZERO; 2],
            seed: 0,
            slope: None,
        };
        let mut t = Totals::default();
        shadow(&view, &cfg, &lookup, &mut t);
        let texels = u64::from(n) * u64::from(n);
        prop_assert_eq!((t.map_reads_z1, t.map_reads_z2), (texels, if midpoint { texels } else { 0 }));
        prop_assert_eq!(t.map_read_bytes, BYTES * t.map_reads());
        prop_assert_eq!(t.lookups_culled, 0);
    }
}

/// The silhouette unit: the horizontal edge of the silhouette picture test
/// (row 3, columns 1 to 5 of the 9 × 7 grid, worked by hand there) is five
/// fragments, each storing a 4-byte point.
#[test]
fn the_silhouette_unit_reports_its_writes() {
    let mut t = Totals::default();
    horizontal_silhouette_edge(&mut t);
    assert_eq!((t.silhouette_fragments, t.silhouette_stored, t.silhouette_write_bytes), (5, 5, 20));
}
