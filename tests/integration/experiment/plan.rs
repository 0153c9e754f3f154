//! The planner: for every bundled scene, the configuration it picks meets
//! the error budget when rendered, and costs no more than the full
//! configuration (dual unit, 24-bit depth) at the same map size and filter.

use umbra::sim::experiment::plan::{PlanSpec, plan};
use umbra::sim::render::Algorithm;
use umbra::sim::world::scene::Scene;
use umbra::sim::world::scene_file::BUNDLED;

/// The budget the tests give: 1 % artifacts at a 192×108 image. At
/// that size one pixel is about 0.01 % of those evaluated, so much tighter
/// budgets would hinge on a handful of pixels.
const BUDGET: f64 = 1.0;

#[test]
fn plans_meet_their_budget_and_cost_no_more_than_the_full_configuration() {
    for (name, _) in BUNDLED {
        let scene = Scene::bundled(name).expect("bundled");
        let mut spec = PlanSpec::new(&scene, BUDGET);
        spec.image = [192, 108];
        spec.map_sizes = vec![128, 256, 512, 1024];
        let p = plan(&scene, &spec).expect("plans");
        println!("{}", p.markdown(&scene, BUDGET));
        assert!(p.meets(BUDGET), "{name}: measured {:.3} % > {BUDGET} %", p.measured.artifact_percent);
        assert!(
            p.measured.cycles <= p.full.cycles && p.measured.bytes <= p.full.bytes,
            "{name}: {:?} costs more than the full configuration {:?}",
            p.measured,
            p.full
        );
        let open = scene.objects.iter().any(|o| !o.solid);
        assert_eq!(
            matches!(p.config.algorithm, Algorithm::Dual { .. }),
            open,
            "{name}: a second buffer only for open surfaces"
        );
    }
}
