//! Which keys a machine's units read, held to the model itself: on every
//! bundled machine, each key `Arch::unread` names is changed and four
//! renders that wake every unit (a second-depth map with bilinear
//! lookups, a first-depth map, a silhouette map, shadow volumes) cost
//! exactly the same, every figure of the report; and each such key, on a
//! machine where it is read, changes some figure (the table is not
//! vacuous). `arch check` warns of the case.

use umbra::core::shadow::Filter;
use umbra::sim::Algorithm;
use umbra::sim::cost::arch::{Arch, PARAMS, Unit, Value};
use umbra::sim::input::limits::Limits;
use umbra::sim::render::{RenderConfig, cost};
use umbra::sim::world::scene::Scene;

/// The report as JSON, less the architecture it records.
fn costs(arch: &Arch) -> Vec<serde_json::Value> {
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let base = RenderConfig { width: 96, height: 54, map_size: 128, reference_rays: 1, ..RenderConfig::DEFAULT };
    [
        RenderConfig { algorithm: Algorithm::Dual { offset: 0.005 }, filter: Filter::Bilinear, ..base },
        RenderConfig { algorithm: Algorithm::First, bias: 0.002, ..base },
        RenderConfig { algorithm: Algorithm::Silhouette { packed: false }, filter: Filter::Point, bias: 0.002, ..base },
        RenderConfig { algorithm: Algorithm::Volumes, ..base },
    ]
    .iter()
    .map(|cfg| {
        let job = cfg.check(&scene, &Limits::DEFAULT).expect("valid");
        let mut v = serde_json::to_value(cost(&job, arch).expect("costs")).expect("JSON");
        v.as_object_mut().expect("an object").remove("arch");
        v
    })
    .collect()
}

/// `arch` with `key` changed to each other value (of a few) the machine
/// accepts: doubled, halved, one more, its range's ends.
fn changed(arch: &Arch, key: &str) -> Vec<Arch> {
    let p = PARAMS.iter().find(|p| p.key == key).expect("a key");
    let suffix = match p.unit {
        Unit::Bytes => "B",
        Unit::Bandwidth => "B/s",
        Unit::Frequency => "Hz",
        Unit::Time => "s",
        Unit::Joules => "J",
        _ => "",
    };
    let candidates: Vec<String> = match arch.get(key).expect("a key") {
        Value::Flag(f) => vec![(!f).to_string()],
        Value::Number(x) => {
            let (min, max) = p.range.unwrap_or((0.0, 1e9));
            [x * 2.0, x / 2.0, x + 1.0, x * 4.0, min, max, 1e-12, 5e-12]
                .into_iter()
                .filter(|v| *v != x && (min..=max).contains(v))
                .map(|v| format!("{v}{suffix}"))
                .collect()
        }
        Value::Text(_) => Vec::new(),
    };
    let accepted: Vec<Arch> = candidates
        .iter()
        .filter_map(|v| {
            let mut a = arch.clone();
            a.set(&format!("{key}={v}")).ok().map(|()| a)
        })
        .collect();
    assert!(!accepted.is_empty(), "{}: no other value of {key} is accepted", arch.name);
    accepted
}

#[test]
fn a_key_no_unit_reads_changes_no_figure() {
    let mut conditional: Vec<&str> = Vec::new();
    let archs = Arch::presets().expect("bundled");
    for arch in &archs {
        let unread = arch.unread();
        assert!(!unread.is_empty(), "{}: every bundled machine leaves some unit out", arch.name);
        let before = costs(arch);
        for u in &unread {
            for b in changed(arch, u.key) {
                let to = b.get(u.key);
                assert_eq!(costs(&b), before, "{}: {} = {to:?} is called unread ({})", arch.name, u.key, u.why);
            }
            if !conditional.contains(&u.key) {
                conditional.push(u.key);
            }
        }
    }
    // Where a machine reads the key, changing it moves some figure.
    for key in conditional {
        let moves = archs
            .iter()
            .filter(|a| !a.unread().iter().any(|u| u.key == key))
            .any(|a| changed(a, key).iter().any(|b| costs(b) != costs(a)));
        assert!(moves, "{key}: no machine that reads it costs differently with another value");
    }
}

/// The case: `depth.peel_cycles = 50` on talisman, whose cost is
/// the same as with 0, is now a warning naming the key that makes it so;
/// ours: a map-cache geometry with no map cache is listed but not warned
/// of, and a depth cache beside buffers all on chip is warned of.
#[test]
fn arch_check_warns_of_a_key_set_to_no_effect() {
    let mut talisman = Arch::bundled("talisman").expect("bundled");
    talisman.set("depth.peel_cycles=50").expect("in range");
    let w = talisman.warnings();
    assert!(
        w.iter().any(|(k, why)| *k == "depth.peel_cycles" && why.contains("depth.second_depth_pass is false")),
        "{w:?}"
    );
    let mut pixelflow = Arch::bundled("pixelflow").expect("bundled");
    assert!(pixelflow.unread().iter().any(|u| u.key == "map_cache.ways" && !u.meant));
    assert!(!pixelflow.warnings().iter().any(|(k, _)| k.starts_with("map_cache")), "{:?}", pixelflow.warnings());
    pixelflow.set("depth_cache.size=16KiB").expect("a cache");
    assert!(pixelflow.warnings().iter().any(|(k, why)| *k == "depth_cache.size" && why.contains("on chip")));
}

/// Sen et al.'s figures only where the render has what they count: a
/// plain shadow map's report gives its map bytes against their model and
/// no `P` or `O` (it printed both as zeros); a silhouette map's gives `P`,
/// shadow volumes' give `O`.
#[test]
fn sens_figures_only_where_they_apply() {
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let talisman = Arch::bundled("talisman").expect("bundled");
    let base = RenderConfig { width: 96, height: 54, map_size: 128, reference_rays: 1, ..RenderConfig::DEFAULT };
    let report = |algorithm| {
        let cfg = RenderConfig { algorithm, filter: Filter::Point, bias: 0.002, ..base };
        cost(&cfg.check(&scene, &Limits::DEFAULT).expect("valid"), &talisman).expect("costs").markdown()
    };
    let plain = report(Algorithm::First);
    assert!(!plain.contains("P = ") && !plain.contains("O = ") && plain.contains("4 B × samples"), "{plain}");
    let silhouette = report(Algorithm::Silhouette { packed: false });
    assert!(silhouette.contains("Sen et al.: P = ") && !silhouette.contains("O = "), "{silhouette}");
    let volumes = report(Algorithm::Volumes);
    assert!(volumes.contains("Sen et al.: O = ") && !volumes.contains("P = "), "{volumes}");
}
