//! Architecture models: closed-form counts worked by hand from the
//! parameters, and totals recomputed independently from the fragments.

use umbra::core::glam::Vec4;
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthFormatKind, DepthUnit, LightPassConfig, RasterConfig};
use umbra::sim::cost::arch::{ArchParams, ArchProbe, Stage, Tee};

use crate::common::{Recorder, run, triangles};

/// The map-filling quad (two triangles) at depth ½.
fn quad() -> Vec<[Vec4; 3]> {
    let v = |x: f32, y: f32| Vec4::new(x, y, 0.5, 1.0);
    vec![[v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0)], [v(-1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)]]
}

fn pass<F: DepthFormat>(p: ArchParams, unit: DepthUnit, tris: &[[Vec4; 3]], size: u32) -> ArchProbe {
    let raster = RasterConfig::new(size, size, p.tile, 8).expect("valid");
    let cfg = LightPassConfig { raster, unit, max_z_cull: false };
    run::<F, _, 64>(cfg, tris, CullMode::None, 64, ArchProbe::new(p, F::KIND, unit)).1
}

fn stage(a: &ArchProbe, s: Stage) -> u64 {
    a.cycles[Stage::ALL.iter().position(|&x| x == s).expect("a stage")]
}

/// Talisman, 64² map, 32-pixel chunks, 24-bit single depth, one quad:
/// 2 setups × 20 cycles; 4096 fragments at 2 per clock = 2048 raster and
/// 2048 depth cycles (each chunk's fragment counts are even: the diagonal
/// chunks split 528 + 496); the resolve writes 4 chunks × 1024 texels × 3
/// bytes = 12 288 bytes at 8 bytes per cycle = 1536 cycles; the bins hold
/// each triangle in 3 chunks: 2 × (3 × 4 + 64) = 152 bytes per triangle.
#[test]
fn talisman_quad_by_hand() {
    let a = pass::<D24>(ArchParams::TALISMAN, DepthUnit::Single, &quad(), 64);
    assert_eq!(a.cycles, [40, 2048, 2048, 0, 1536]);
    assert_eq!((a.dram.map_writes, a.dram.map_rmw_reads, a.dram.bins, a.dram.map_reads), (12_288, 0, 304, 0));
    assert_eq!(a.bottleneck(), (Stage::Depth, 2048));
    assert_eq!(a.on_chip_bytes(), 32 * 32 * 3);
}

/// PixelFlow: the 64² map is one 128² region, so each triangle costs the
/// evaluator 4 × 32 cycles and the bit-serial depth unit 2 × bits cycles,
/// whatever its 2048 fragments; 24 bits cost 1.5× 16 bits.
#[test]
fn pixelflow_quad_by_hand_and_depth_bits() {
    let a24 = pass::<D24>(ArchParams::PIXELFLOW, DepthUnit::Single, &quad(), 64);
    let a16 = pass::<D16>(ArchParams::PIXELFLOW, DepthUnit::Single, &quad(), 64);
    assert_eq!(stage(&a24, Stage::Setup), 200);
    assert_eq!(stage(&a24, Stage::Raster), 2 * 128);
    assert_eq!(stage(&a24, Stage::Depth), 2 * 2 * 24);
    assert_eq!(stage(&a16, Stage::Depth), 2 * 2 * 16);
    assert_eq!(2 * stage(&a24, Stage::Depth), 3 * stage(&a16, Stage::Depth));
    // Dual keeps two buffers: twice the depth-unit cycles.
    let dual = pass::<D24>(ArchParams::PIXELFLOW, DepthUnit::Dual, &quad(), 64);
    assert_eq!(stage(&dual, Stage::Depth), 2 * stage(&a24, Stage::Depth));
}

/// Talisman's resolve writes only the value the shadow test needs: the dual
/// unit writes the same bytes as the single one.
#[test]
fn talisman_dual_resolve_writes_what_single_does() {
    let scene: Vec<[Vec4; 3]> = quad()
        .into_iter()
        .chain(quad().into_iter().map(|t| t.map(|v| Vec4::new(v.x * 0.5, v.y * 0.5, 0.3, 1.0))))
        .collect();
    let single = pass::<D24>(ArchParams::TALISMAN, DepthUnit::Single, &scene, 128);
    let dual = pass::<D24>(ArchParams::TALISMAN, DepthUnit::Dual, &scene, 128);
    assert_eq!(single.dram.map_writes, dual.dram.map_writes);
    assert_eq!(single.dram.map_writes, 128 * 128 * 3);
    // But the dual unit does twice the depth work.
    assert_eq!(stage(&dual, Stage::Depth), 2 * stage(&single, Stage::Depth));
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]

    /// The immediate-mode preset's DRAM traffic equals what a replay of the
    /// recorded fragments through a plain z-buffer reads and writes, and its
    /// raster cycles what the fragments per triangle and tile need at 2 per
    /// clock.
    #[test]
    fn immediate_totals_equal_a_replay_of_the_fragments(tris in triangles(20)) {
        let raster = RasterConfig::new(64, 64, 32, 8).expect("valid");
        let cfg = LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true };
        let probe = Tee(ArchProbe::new(ArchParams::IMMEDIATE, DepthFormatKind::D16, DepthUnit::Single), Recorder::default());
        let (_, Tee(a, rec)) = run::<D16, _, 64>(cfg, &tris, CullMode::None, 64, probe);
        let mut z = vec![u32::MAX; 64 * 64];
        let mut writes = 0u64;
        let mut per_pair = std::collections::BTreeMap::new();
        for f in &rec.fragments {
            let t = &mut z[(f.y * 64 + f.x) as usize];
            if f.depth < *t {
                *t = f.depth;
                writes += 1;
            }
            *per_pair.entry((f.triangle, f.x / 32, f.y / 32)).or_insert(0u64) += 1;
        }
        let n = rec.fragments.len() as u64;
        proptest::prop_assert_eq!(a.dram.map_rmw_reads, n * 2);
        proptest::prop_assert_eq!(a.dram.map_writes, writes * 2);
        let raster: u64 = per_pair.values().map(|c| c.div_ceil(2)).sum();
        proptest::prop_assert_eq!(stage(&a, Stage::Raster), raster);
    }
}
