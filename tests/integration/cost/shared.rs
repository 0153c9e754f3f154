//! One render per configuration: the functional render's passes cost the
//! architectures that draw as it does, and architectures sharing any other
//! tiling share one run of the passes — with the same reports, bit for bit,
//! as costing each alone, and the same render.

use umbra::core::DepthFormatKind;
use umbra::core::shadow::Filter;
use umbra::sim::Algorithm;
use umbra::sim::cost::arch::Arch;
use umbra::sim::input::limits::Limits;
use umbra::sim::render::{RenderConfig, TruthSource, cost, render, render_costed};
use umbra::sim::world::scene::Scene;

#[test]
fn a_shared_pass_costs_each_architecture_as_alone() {
    // Every bundled architecture, and talisman and pixelflow twice more with
    // another cache and DRAM: groups of one, two and three per tiling.
    let mut archs = Arch::presets().expect("bundled");
    for (name, set) in [("talisman", "map_cache.size=64KiB"), ("pixelflow", "dram.bandwidth=9.6GB/s")] {
        let mut a = Arch::bundled(name).expect("bundled");
        a.set(set).expect("valid");
        archs.push(a);
    }
    let limits = Limits::DEFAULT;
    for (scene, algorithm, filter) in [
        ("table-and-sphere", Algorithm::Second, Filter::Bilinear),
        ("crowd", Algorithm::Silhouette { packed: false }, Filter::Point),
        ("weiskopf-l", Algorithm::Volumes, Filter::Point),
    ] {
        let s = Scene::bundled(scene).expect("bundled");
        let cfg = RenderConfig {
            algorithm,
            format: DepthFormatKind::D16,
            map_size: 256,
            filter,
            bias: 0.002,
            virtual_samples: true,
            width: 160,
            height: 96,
            reference_rays: 1,
            ..RenderConfig::DEFAULT
        };
        let alone = cfg
            .check(&s, &limits)
            .and_then(|job| render(&job, TruthSource::Build(&indicatif::ProgressBar::hidden())))
            .expect("renders");
        let (shared, costs) = cfg
            .check(&s, &limits)
            .and_then(|job| render_costed(&job, TruthSource::Given(vec![alone.truth.clone()]), &archs))
            .expect("renders");
        assert_eq!(shared.image.pixels, alone.image.pixels, "{scene}");
        assert_eq!(shared.metrics, alone.metrics, "{scene}");
        assert_eq!(shared.camera_events.totals, alone.camera_events.totals, "{scene}");
        assert_eq!(costs.len(), archs.len());
        for (a, c) in archs.iter().zip(&costs) {
            let one = serde_json::to_string(&cfg.check(&s, &limits).and_then(|job| cost(&job, a)).expect("costed"))
                .expect("JSON");
            let together = serde_json::to_string(c.as_ref().expect("costed")).expect("JSON");
            assert!(one == together, "{scene} on {}: costed alone and shared differ", a.name);
        }
    }
}
