//! An architecture's derived figures and warnings against numbers worked
//! by hand: the 1.1 GHz copy of `mobile-tbdr` with 76.8 GB/s,
//! whose 180 requests of 64 B in flight at 225 ns cap it at Little's
//! 180 × 64 B / 225 ns = 51.2 GB/s.

use umbra::sim::cost::arch::Arch;
use umbra::sim::cost::arch::derived::diff;

fn faster() -> Arch {
    let mut a = Arch::bundled("mobile-tbdr").expect("bundled");
    a.set("clock=1.1GHz").expect("valid");
    a.set("dram.bandwidth=76.8GB/s").expect("valid");
    a
}

fn figure(a: &Arch, name: &str) -> f64 {
    a.derived().into_iter().find(|f| f.name == name).unwrap_or_else(|| panic!("{name}")).value
}

#[test]
fn the_latency_ceiling_caps_the_bandwidth_and_is_warned_about() {
    let a = faster();
    // 180 × 64 / 225e-9 = 51.2e9 B/s, worked by hand.
    assert!((figure(&a, "DRAM latency ceiling") - 51.2e9).abs() < 1.0);
    assert!((figure(&a, "DRAM achievable") - 51.2e9).abs() < 1.0);
    // 51.2e9 / 1.1e9 = 46.545… bytes a clock; 225 ns × 1.1 GHz = 247.5 clocks.
    assert!((figure(&a, "DRAM bytes a clock") - 46.545_454).abs() < 1e-3);
    assert!((figure(&a, "DRAM latency in clocks") - 247.5).abs() < 1e-9);
    let w = a.warnings();
    assert!(w.iter().any(|(k, t)| *k == "dram.bandwidth" && t.contains("51.2GB/s")), "{w:?}");
    // 76.8 GB/s × 225 ns / 64 B = 270 requests would use the bandwidth.
    assert!(w.iter().any(|(_, t)| t.contains("270 requests")), "{w:?}");
    // Doubled, the ceiling is 102.4 GB/s: the bandwidth binds, no warning.
    let mut doubled = a.clone();
    doubled.set("dram.requests_in_flight=360").expect("valid");
    assert!((figure(&doubled, "DRAM achievable") - 76.8e9).abs() < 1.0);
    assert!(!doubled.warnings().iter().any(|(k, _)| *k == "dram.bandwidth"));
}

#[test]
fn cache_geometry_and_tile_buffers_are_worked_out() {
    let a = Arch::bundled("mobile-tbdr").expect("bundled");
    // 1 MiB of 64-byte lines, 16 ways: 1048576 / (64 × 16) = 1024 sets.
    assert_eq!(figure(&a, "map cache sets"), 1024.0);
    // 180 misses × 64 B / 225 ns = 51.2 GB/s, as the DRAM's ceiling.
    assert!((figure(&a, "map cache miss ceiling") - 51.2e9).abs() < 1.0);
    let tile = f64::from(a.raster.tile);
    assert_eq!(figure(&a, "light depth a tile"), tile * tile * 8.0);
    assert_eq!(figure(&a, "depth cache size"), 0.0);
}

#[test]
fn a_diff_names_each_changed_key_and_figure() {
    let (a, b) = (Arch::bundled("mobile-tbdr").expect("bundled"), faster());
    let (keys, figures) = diff(&a, &b);
    let names: Vec<&str> = keys.iter().map(|k| k.0).collect();
    assert_eq!(names, ["clock", "dram.bandwidth"]);
    assert_eq!(keys[1], ("dram.bandwidth", "51.2GB/s".to_owned(), "76.8GB/s".to_owned()));
    let changed: Vec<&str> = figures.iter().map(|f| f.0).collect();
    // The achievable bandwidth stays at the 51.2 GB/s ceiling: unchanged.
    assert!(changed.contains(&"DRAM bandwidth") && !changed.contains(&"DRAM achievable"), "{changed:?}");
    assert!(changed.contains(&"raster fill") && changed.contains(&"DRAM latency in clocks"), "{changed:?}");
    assert_eq!(diff(&a, &a), (Vec::new(), Vec::new()));
}
