//! `arch diff --scene`: two architecture files differing in the tile size
//! and the map cache's size, their difference attributed to each key and
//! held to separate runs of each single change; the remainder is what the
//! two single changes do not add up to.

use umbra::sim::cost::arch::Arch;
use umbra::sim::cost::report::CostReport;
use umbra::sim::experiment::attribution::attribute;
use umbra::sim::input::limits::Limits;
use umbra::sim::render::{RenderConfig, cost};
use umbra::sim::world::scene::Scene;

use super::arch::close;

#[test]
fn each_key_s_share_is_its_single_change_run_alone() {
    let scene = Scene::bundled("table-and-sphere").expect("bundled");
    let cfg = RenderConfig { width: 240, height: 135, map_size: 512, ..RenderConfig::DEFAULT };
    let job = cfg.check(&scene, &Limits::DEFAULT).expect("valid");
    let file = |changes: &[&str]| {
        let mut text = Arch::bundled("talisman").expect("bundled").to_toml();
        for c in changes {
            let (key, value) = c.split_once('=').expect("key=value");
            let line = text.lines().find(|l| l.starts_with(&format!("{key} = "))).expect("the key").to_owned();
            text = text.replace(&line, &format!("{key} = {value}"));
        }
        Arch::parse(&text, "b.toml").expect("a file")
    };
    let a = file(&[]);
    let b = file(&["raster.tile=64", "map_cache.size=\"4KiB\""]);
    let t = attribute(&job, &a, &b).expect("attributes");
    let run = |arch: &Arch| cost(&job, arch).expect("costs");
    let (ra, rb) = (run(&a), run(&b));
    let alone = [
        ("raster.tile", run(&file(&["raster.tile=64"]))),
        ("map_cache.size", run(&file(&["map_cache.size=\"4KiB\""]))),
    ];
    let keys: Vec<&str> = t.shares.iter().map(|s| s.key).collect();
    assert_eq!(keys.len(), 2, "{keys:?}");
    let bytes = |r: &CostReport| i64::try_from(r.bytes()).expect("bytes");
    let mut explained = (0.0, 0);
    for (key, r) in &alone {
        let share = t.shares.iter().find(|s| s.key == *key).expect("a share");
        let e = share.effect.as_ref().expect("changes alone");
        assert!(
            close(e.seconds, r.seconds() - ra.seconds()),
            "{key}: {} against {}",
            e.seconds,
            r.seconds() - ra.seconds()
        );
        assert!(close(e.joules, r.energy().total() - ra.energy().total()), "{key}");
        assert_eq!(e.bytes, bytes(r) - bytes(&ra), "{key}");
        assert_eq!(e.bytes_by_purpose.iter().map(|p| p.1).sum::<i64>(), e.bytes, "{key}: purposes add up");
        explained = (explained.0 + e.seconds, explained.1 + e.bytes);
    }
    assert!(close(t.total.seconds, rb.seconds() - ra.seconds()));
    assert!(close(t.remainder.seconds, (rb.seconds() - ra.seconds()) - explained.0), "{:?}", t.remainder);
    assert_eq!(t.remainder.bytes, (bytes(&rb) - bytes(&ra)) - explained.1);
    // Ranked by the size of the effect on time.
    let size = |k: usize| t.shares[k].effect.as_ref().map_or(0.0, |e| e.seconds.abs());
    assert!(size(0) >= size(1), "{:?}", t.shares);
    // Both changes move DRAM bytes: the tile the bins and resolves, the
    // cache the map's fetches.
    assert!(t.shares.iter().all(|s| s.effect.as_ref().is_some_and(|e| e.bytes != 0)), "{:?}", t.shares);
}
