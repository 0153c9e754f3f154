//! Silicon: each unit's area worked by hand for one small architecture,
//! and the SRAM model against published macro densities.

use umbra::sim::Arch;
use umbra::sim::cost::silicon::{Demand, Kind, Silicon};

/// Talisman with round figures: a 1 µm² bit cell in arrays half cells, a
/// 1 µm² gate, 1 W/mm² of leakage.
fn round_talisman() -> Arch {
    let mut a = Arch::bundled("talisman").expect("bundled");
    for s in ["technology.sram_bit=1um2", "technology.array_efficiency=0.5", "technology.gate=1um2"] {
        a.set(s).expect("valid");
    }
    a.set("technology.leakage=1W/mm2").expect("valid");
    a
}

/// The areas of `s`'s units in µm², by name.
fn areas(s: &Silicon) -> Vec<(&str, f64)> {
    s.units.iter().map(|u| (u.unit, u.square_metres * 1e12)).collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// First depth in D16 with a point filter on Talisman (32² tiles, 2
/// fragments and 4 samples a clock, a 16 KiB 4-way map cache of 64 B
/// lines), worked by hand.
#[test]
fn first_depth_on_talisman_by_hand() {
    let d = Demand {
        depth_buffers: 1,
        depth_bits: 16,
        map: [256, 256],
        image: [160, 90],
        buffers_read: 1,
        samples_per_lookup: 1,
        bilinear: false,
        ..Demand::DEFAULT
    };
    let s = Silicon::of(&round_talisman(), &d);
    let want = [
        // 1 buffer × 32² texels × 16 bits = 16 384 bits, over 0.5.
        ("light depth buffers", 32_768.0),
        // 16 KiB: 256 lines in 64 sets; a tag of 40 − 6 (sets) − 6 (line)
        // = 28 bits, valid, 2 bits of LRU: 131 072 + 256 × 31 = 139 008
        // bits, over 0.5.
        ("map cache", 278_016.0),
        // 32² pixels × (24 + 32) bits = 57 344 bits, over 0.5.
        ("camera depth and ids", 114_688.0),
        // The larger target: the map's 8 × 8 tiles (the image's 5 × 3
        // fewer), a 32-bit head each: 2048 bits, over 0.5.
        ("bin heads", 4096.0),
        // 2 lanes × (a 48-bit adder at 6.9 gates a bit + a 16-bit
        // comparator at 7): 2 × (331.2 + 112) gates of 1 µm².
        ("light depth test", 886.4),
        // 4 sample lanes × (a 16-bit comparator + a 16-bit bias adder):
        // 4 × (112 + 110.4).
        ("shadow compare", 889.6),
    ];
    let got = areas(&s);
    assert_eq!(got.len(), want.len(), "{got:?}");
    for ((unit, area), (w_unit, w_area)) in got.iter().zip(want) {
        assert_eq!(*unit, w_unit);
        assert!(close(*area, w_area), "{unit}: {area} µm², by hand {w_area}");
    }
    let total = 431_344.0;
    assert!(close(s.square_metres() * 1e12, total), "{}", s.square_metres() * 1e12);
    // 1 W/mm² over 0.431 344 mm².
    assert!(close(s.leakage_watts(), 0.431_344), "{}", s.leakage_watts());
    assert!(s.units.iter().take(4).all(|u| u.kind == Kind::Storage));
}

/// What a second buffer, 24 bits and a bilinear filter add, each by hand:
/// the demand's units differ exactly where the hardware does.
#[test]
fn a_second_buffer_wider_texels_and_bilinear_weights_by_hand() {
    let a = round_talisman();
    let first = Demand { depth_buffers: 1, depth_bits: 16, samples_per_lookup: 1, bilinear: false, ..Demand::DEFAULT };
    let dual = Demand { depth_buffers: 2, ..first };
    let wide = Demand { depth_bits: 24, ..first };
    let bilinear = Demand { samples_per_lookup: 4, bilinear: true, ..first };
    let area = |d: &Demand, unit: &str| {
        areas(&Silicon::of(&a, d)).into_iter().find(|(u, _)| *u == unit).map_or(0.0, |(_, x)| x)
    };
    // Two buffers: twice the bits, a second comparator per lane.
    assert!(close(area(&dual, "light depth buffers"), 65_536.0));
    assert!(close(area(&dual, "light depth test"), 2.0 * (331.2 + 2.0 * 112.0)));
    // 24 bits: half as many bits again; a 56-bit interpolator, 24-bit
    // comparators and adders.
    assert!(close(area(&wide, "light depth buffers"), 49_152.0));
    assert!(close(area(&wide, "light depth test"), 2.0 * (6.9 * 56.0 + 7.0 * 24.0)));
    assert!(close(area(&wide, "shadow compare"), 4.0 * (7.0 * 24.0 + 6.9 * 24.0)));
    // Bilinear: one lookup lane of four samples, four 16×16 multipliers
    // at 7.7 gates a bit pair and three 32-bit adders.
    assert!(close(area(&bilinear, "filter weights"), 4.0 * 7.7 * 256.0 + 3.0 * 6.9 * 32.0));
    assert!(area(&first, "filter weights") == 0.0);
    // A silhouette map: its points' bits on chip and the evaluator.
    let sil = Demand { silhouette_bits: 32, samples_per_lookup: 4, ..first };
    assert!(close(area(&sil, "silhouette points"), 65_536.0));
    assert!(close(area(&sil, "silhouette evaluator"), 4.0 * (2.0 * 7.7 * 289.0 + 6.9 * 34.0)));
    // Shadow volumes: no map, so no map cache, light buffers or shadow
    // unit; a stencil and its unit instead.
    let vol = Silicon::of(&a, &Demand { volumes: true, ..first });
    let names: Vec<&str> = vol.units.iter().map(|u| u.unit).collect();
    assert_eq!(names, ["camera depth and ids", "stencil", "bin heads", "stencil unit"]);
}

/// The SRAM model against WikiChip's macro densities for TSMC's N3 cells
/// ("IEDM 2022: Did We Just Witness The Death Of SRAM?", 2022): 31.8
/// Mib/mm² for N3E's 0.021 µm² cell, 33.55 Mib/mm² for N3B's 0.0199 µm²,
/// both at the bundled files' 70 % array efficiency. One Mib is a 128²
/// tile of two 32-bit buffers (2 × 32 × 2¹⁴ = 2²⁰ bits); the published
/// figures have three and four significant digits, so within 0.2 %.
#[test]
fn sram_density_reproduces_the_published_macros() {
    let mut a = Arch::bundled("mobile-tbdr").expect("bundled");
    a.set("raster.tile=128").expect("valid");
    let mib = Demand { depth_buffers: 2, depth_bits: 32, ..Demand::DEFAULT };
    for (cell, published) in [("0.021um2", 31.8), ("0.0199um2", 33.55)] {
        a.set(&format!("technology.sram_bit={cell}")).expect("valid");
        let s = Silicon::of(&a, &mib);
        let buffers = s.units.iter().find(|u| u.unit == "light depth buffers").expect("on chip");
        assert_eq!(buffers.size, f64::from(1u32 << 20));
        let density = 1.0 / (buffers.square_metres * 1e6);
        assert!((density / published - 1.0).abs() < 0.002, "{cell}: {density:.3} Mib/mm², published {published}");
    }
}
