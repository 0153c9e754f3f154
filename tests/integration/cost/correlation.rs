//! The timing model against published hardware: Weiskopf & Ertl's Table 1
//! frame-rate ratios on a Radeon 9700, recomputed for the bundled `r300`
//! architecture and `factory` scene, and held to the table the README
//! prints (so the README cannot drift from the model).

use umbra::sim::cost::arch::Arch;
use umbra::sim::experiment::correlation::{NO_SHADOW_FPS, TABLE_1, run};
use umbra::sim::io::limits::Limits;
use umbra::sim::world::scene::Scene;

#[test]
fn table_1_ratios_follow_the_published_frame_rates() {
    let scene = Scene::bundled("factory").expect("bundled");
    assert_eq!(scene.objects.iter().map(|o| o.mesh.triangles.len()).sum::<usize>(), 13_284, "their count");
    assert_eq!(scene.image, [1100, 1100]);
    let c = run(&scene, &Arch::bundled("r300").expect("bundled"), &Limits::DEFAULT).expect("costs");
    assert_eq!(c.cells.len(), 12);
    for (cell, (_, _, published)) in c.cells.iter().zip(TABLE_1.iter().flat_map(|r| std::iter::repeat_n(r, 4))) {
        // The published ratio, worked from their frame rates.
        assert!(published.contains(&cell.published_fps));
        assert!((cell.published_ratio - cell.published_fps / NO_SHADOW_FPS).abs() < 1e-12);
    }
    // Shadows cost time: every predicted ratio is below one, a second
    // depth costs more than a first, a bigger map and more samples too.
    let ratio = |filter: &str, method: &str, map: u32| {
        c.cells
            .iter()
            .find(|x| x.filter == filter && x.method == method && x.map == map)
            .expect("a cell")
            .predicted_ratio
    };
    for (filter, _, _) in TABLE_1 {
        for map in [256, 2048] {
            assert!(ratio(filter, "midpoint / dual", map) < ratio(filter, "constant bias", map));
        }
        for method in ["constant bias", "midpoint / dual"] {
            assert!(ratio(filter, method, 2048) < ratio(filter, method, 256));
        }
    }
    assert!(ratio("4×4", "constant bias", 256) < ratio("bilinear", "constant bias", 256));
    assert!(ratio("bilinear", "constant bias", 256) < ratio("no filtering", "constant bias", 256));
    assert!(c.cells.iter().all(|x| x.predicted_ratio < 1.0));
}
