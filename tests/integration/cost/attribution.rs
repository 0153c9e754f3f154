//! `arch diff --scene`: two architecture files differing in the tile size
//! and the map cache's size, their difference attributed to each key by
//! Shapley value and held to the two-player formula worked by hand from
//! separate runs of each single change; the shares add up to the
//! difference, and the other way round they are its negative.

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
    let tile = run(&file(&["raster.tile=64"]));
    let cache = run(&file(&["map_cache.size=\"4KiB\""]));
    let keys: Vec<&str> = t.shares.iter().flat_map(|s| s.keys.iter().map(|k| k.key)).collect();
    assert_eq!(keys.len(), 2, "{keys:?}");
    let bytes = |r: &CostReport| r.bytes() as f64;
    // Two players, worked by hand: each key's share is the mean of its
    // effect first (from a) and its effect last (into b).
    for (key, alone, other) in [("raster.tile", &tile, &cache), ("map_cache.size", &cache, &tile)] {
        let share = t.shares.iter().find(|s| s.keys[0].key == key).expect("a share");
        let by_hand = |f: &dyn Fn(&CostReport) -> f64| 0.5 * (f(alone) - f(&ra)) + 0.5 * (f(&rb) - f(other));
        let seconds = by_hand(&|r| r.seconds());
        assert!(close(share.share.seconds, seconds), "{key}: {} against {seconds}", share.share.seconds);
        assert!(close(share.share.joules, by_hand(&|r| r.energy().total())), "{key}");
        // The tile's buffers and the cache's bits are silicon; the area
        // of either does not depend on the other, so a share is its own.
        let area = by_hand(&|r| r.square_metres());
        assert!(close(share.share.square_metres, area) && area != 0.0, "{key}: {area}");
        assert!(close(share.alone.square_metres, alone.square_metres() - ra.square_metres()), "{key}");
        assert!(close(share.share.square_metres, share.alone.square_metres), "{key}: no interaction in area");
        assert_eq!(share.share.bytes, by_hand(&bytes), "{key}: half-bytes are exact");
        assert!(close(share.alone.seconds, alone.seconds() - ra.seconds()), "{key}: alone");
        let purposes: f64 = share.share.bytes_by_purpose.iter().map(|p| p.1).sum();
        assert_eq!(purposes, share.share.bytes, "{key}: purposes add up");
    }
    // The shares add up to the difference, with no remainder.
    let (seconds, b_bytes): (f64, f64) =
        t.shares.iter().map(|s| (s.share.seconds, s.share.bytes)).fold((0.0, 0.0), |a, x| (a.0 + x.0, a.1 + x.1));
    assert!((seconds - (rb.seconds() - ra.seconds())).abs() <= 1e-12 * ra.seconds());
    assert_eq!(b_bytes, bytes(&rb) - bytes(&ra));
    // Ranked by the size of the effect on time.
    assert!(t.shares[0].share.seconds.abs() >= t.shares[1].share.seconds.abs(), "{:?}", t.shares);
    // The other way round: key by key the negative, bit for bit.
    let back = attribute(&job, &b, &a).expect("attributes");
    for s in &t.shares {
        let o = back.shares.iter().find(|o| o.keys[0].key == s.keys[0].key).expect("the same key");
        assert_eq!(o.share.seconds, -s.share.seconds, "{}", s.keys[0].key);
        assert_eq!(o.share.bytes, -s.share.bytes);
        assert_eq!(o.share.joules, -s.share.joules);
        assert_eq!(o.share.square_metres, -s.share.square_metres);
        assert_eq!((&o.keys[0].values.0, &o.keys[0].values.1), (&s.keys[0].values.1, &s.keys[0].values.0));
    }
    assert_eq!(back.total.seconds, -t.total.seconds);
}
