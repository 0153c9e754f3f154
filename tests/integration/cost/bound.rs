//! What binds, told apart: memory bound by its bandwidth or by its latency
//! (worked by hand), cache statistics of a hand-worked stream, time as the
//! cost common to architectures of different clocks, and the stats file's
//! one convention.

use std::collections::HashMap;

use umbra::core::shadow::Filter;
use umbra::core::{D24, DepthFormatKind, DepthUnit};
use umbra::sim::Algorithm;
use umbra::sim::cost::arch::Arch;
use umbra::sim::cost::cache::Cache;
use umbra::sim::cost::report::files::write_costs;
use umbra::sim::cost::report::{Comparison, CostReport};
use umbra::sim::cost::work::Bottleneck;
use umbra::sim::input::limits::Limits;
use umbra::sim::output::folder::OutputFolder;
use umbra::sim::render::{RenderConfig, cost};
use umbra::sim::world::scene::Scene;

use super::arch::{bundled, close, pass, quad};

/// Talisman with fast compute (64 fragments a clock: 16 raster and 16
/// depth cycles a chunk) and `in_flight` DRAM requests, read back from its
/// own file text.
fn talisman_file(in_flight: u32) -> Arch {
    let mut a = bundled("talisman");
    for s in ["raster.fragments_per_clock=64", "depth.fragments_per_clock=64"] {
        a.set(s).expect("valid");
    }
    a.set(&format!("dram.requests_in_flight={in_flight}")).expect("valid");
    Arch::parse(&a.to_toml(), "slow-dram.toml").expect("its own text parses")
}

/// Talisman's quad (`arch.rs`): four 32² chunks of a 64² 24-bit map,
/// 1.2 GB/s = 16 bytes a cycle at 75 MHz, 50 ns = 3.75 cycles, 32-byte
/// bursts. The two diagonal chunks stream 3208 bytes (101 bursts), the
/// other two 3140 (99 bursts); the front end writes 152 bytes of bins
/// (5 bursts), overlapped with the chunks, sharing the DRAM.
///
/// * One request in flight: the latency ceiling is 32 B / 50 ns =
///   640 MB/s, below the 1.2 GB/s: a chunk's memory is its bursts at the
///   latency, 101 × 3.75 = 378.75 or 99 × 3.75 = 371.25 cycles (its bytes
///   at the bandwidth only 200.5 or 196.25), and the pass is the shared
///   DRAM, 2 × 378.75 + 2 × 371.25 + 5 × 3.75 = 1518.75 cycles, bound by
///   the latency in every chunk. `arch check` warns about the bandwidth.
/// * Two in flight (1.28 GB/s of ceiling): the latency halves below the
///   bytes at the bandwidth (189.375 < 200.5), so every byte moves at the
///   bandwidth: (2 × 3208 + 2 × 3140 + 152) / 16 = 803 cycles, 10.7067 µs,
///   and the achieved rate is the peak, 1.2 GB/s.
#[test]
fn latency_bound_then_bandwidth_bound_by_hand() {
    let slow = talisman_file(1);
    assert!(slow.warnings().iter().any(|(key, _)| *key == "dram.bandwidth"), "{:?}", slow.warnings());
    let t = pass::<D24>(&slow, DepthUnit::Single, &quad(), 64).timing();
    assert!(close(t.cycles(), 1518.75), "{}", t.cycles());
    assert_eq!(t.bottleneck(), Bottleneck::DramLatency);
    assert_eq!(t.bound[Bottleneck::DramLatency as usize], 4, "{:?}", t.bound);
    assert!(close(t.memory.latency_cycles, 2.0 * 378.75 + 2.0 * 371.25 + 5.0 * 3.75), "{:?}", t.memory);
    assert!(close(t.memory.bandwidth_cycles, 803.0), "{:?}", t.memory);

    let doubled = talisman_file(2);
    assert!(doubled.warnings().iter().all(|(key, _)| *key != "dram.bandwidth"), "{:?}", doubled.warnings());
    let t = pass::<D24>(&doubled, DepthUnit::Single, &quad(), 64).timing();
    assert!(close(t.cycles(), 803.0), "{}", t.cycles());
    assert_eq!(t.bottleneck(), Bottleneck::DramBandwidth);
    assert_eq!(t.bound[Bottleneck::DramBandwidth as usize], 4, "{:?}", t.bound);
    assert!(close(t.cycles() / doubled.clock, 803.0 / 75e6));
    assert!(close(t.achieved_bytes_per_second(), 1.2e9), "{}", t.achieved_bytes_per_second());
}

/// A cache's misses in flight as a queue of their own. The immediate-mode
/// file with fast compute (64 fragments a clock: 64 raster and 64 depth
/// cycles for the quad's 4096), 4.8 GB/s (64 bytes a cycle at 75 MHz),
/// 50 ns = 3.75 cycles of latency, and a 1 MiB depth cache of 64-byte
/// lines keeping `misses` in flight. The 64² 24-bit map's 4-byte slots fill
/// 256 lines, each fetched once by the one draw:
///
/// * one miss in flight: the depth cache's ceiling is 64 B / 50 ns =
///   1.28 GB/s. The draw's misses take 256 × 3.75 = 960 cycles; DRAM's
///   own queue (4 in flight) 256 × 3.75 / 4 = 240, its bytes at the
///   bandwidth 16384 / 64 = 256: the draw is bound by the depth cache's
///   misses at 960 cycles and moves its bytes at exactly the ceiling,
///   16384 B / 960 cycles × 75 MHz = 1.28 GB/s. The flush after it
///   streams the 256 dirty lines back, 512 bursts × 3.75 / 4 = 480 cycles
///   (above 256 at the bandwidth): 1440 cycles. `arch check` names both
///   keys that cap the bandwidth at once: DRAM's 4 × 32 B / 50 ns =
///   2.56 GB/s, and the cache's 1.28 GB/s, with 4 misses in flight
///   (4.8 GB/s × 50 ns / 64 B = 3.75) to use it.
/// * four in flight: the misses take 240 cycles, below the bytes' 256, so
///   the draw is bound by the bandwidth: 256 + 480 = 736 cycles, of
///   which the ledger charges 256 to the bandwidth and the flush's 480 to
///   DRAM's latency — the pass's most, so what bounds it.
#[test]
fn a_cache_s_misses_in_flight_bind_by_hand() {
    let arch = |misses: u32| {
        let mut a = bundled("immediate");
        for s in ["raster.fragments_per_clock=64", "depth.fragments_per_clock=64", "dram.bandwidth=4.8GB/s"] {
            a.set(s).expect("valid");
        }
        a.set("depth_cache.size=1MiB").expect("valid");
        a.set(&format!("depth_cache.misses_in_flight={misses}")).expect("valid");
        a
    };
    let one = arch(1);
    let keys: Vec<&str> = one.warnings().iter().map(|w| w.0).collect();
    assert_eq!(keys, ["dram.bandwidth", "depth_cache.misses_in_flight"], "{:?}", one.warnings());
    let advice = &one.warnings()[1].1;
    assert!(advice.contains("1.28GB/s") && advice.contains("; 4 would use the bandwidth"), "{advice}");
    let ceiling = one.derived().into_iter().find(|f| f.name == "depth cache miss ceiling").expect("a figure");
    assert!(close(ceiling.value, 1.28e9), "{}", ceiling.value);

    let t = pass::<D24>(&one, DepthUnit::Single, &quad(), 64).timing();
    assert_eq!(t.bottleneck(), Bottleneck::DepthCacheMissesInFlight);
    assert_eq!(t.bound[Bottleneck::DepthCacheMissesInFlight as usize], 1, "{:?}", t.bound);
    assert!(close(t.cycles(), 960.0 + 480.0), "{}", t.cycles());
    let [dram, map, depth] = t.memory.queue_cycles;
    assert!(close(depth, 960.0) && close(map, 0.0) && close(dram, 240.0 + 480.0), "{:?}", t.memory);
    assert_eq!(t.bytes(), 2 * 16384);
    assert!(close(16384.0 / (960.0 / one.clock), ceiling.value), "the draw moves its bytes at the ceiling");

    let four = arch(4);
    assert_eq!(four.warnings().iter().map(|w| w.0).collect::<Vec<_>>(), ["dram.bandwidth"]);
    let t = pass::<D24>(&four, DepthUnit::Single, &quad(), 64).timing();
    assert_eq!(t.bound[Bottleneck::DramBandwidth as usize], 1, "{:?}", t.bound);
    let by = |b: Bottleneck| t.bound_cycles[b as usize];
    assert!(close(by(Bottleneck::DramBandwidth), 256.0) && close(by(Bottleneck::DramLatency), 480.0));
    assert_eq!(t.bottleneck(), Bottleneck::DramLatency);
    assert!(close(t.cycles(), 256.0 + 480.0), "{}", t.cycles());
}

/// Two sets of two 32-byte ways (lines 0, 2 and 4 in set 0, line 1 in
/// set 1), written (w) and read (r):
/// w0 miss · r8 hit · r64 miss · w32 miss · r128 miss, evicting dirty
/// line 0 (a write-back) · r0 miss, evicting clean line 2 · w72 miss,
/// evicting clean line 4 · r40 hit; the flush writes back lines 1 and 2.
/// 8 accesses, 2 hits, 6 misses (192 bytes fetched), 3 write-backs (96
/// bytes).
#[test]
fn cache_statistics_of_a_stream_by_hand() {
    let mut c = Cache::new(128, 32, 2).expect("valid");
    let stream = [(0u64, true), (8, false), (64, false), (32, true), (128, false), (0, false), (72, true), (40, false)];
    let hits: Vec<bool> = stream
        .iter()
        .map(|&(address, write)| if write { c.access_write(address).0 } else { c.access(address) })
        .collect();
    assert_eq!(hits, [false, true, false, false, false, false, false, true]);
    assert_eq!(c.stats().written_back_bytes, 32, "only line 0 is dirty when evicted");
    assert_eq!(c.flush(), 2);
    let s = c.stats();
    assert_eq!((s.accesses, s.hits, s.misses), (8, 2, 6));
    assert!(close(s.hit_rate, 0.25));
    assert_eq!((s.fetched_bytes, s.written_back_bytes), (192, 96));
}

/// The bundled table, second depth, 24-bit, 256², bilinear, at 240×135.
pub(super) fn small() -> (Scene, RenderConfig) {
    let cfg = RenderConfig {
        algorithm: Algorithm::Second,
        format: DepthFormatKind::D24,
        map_size: 256,
        filter: Filter::Bilinear,
        bias: 0.0,
        virtual_samples: true,
        width: 240,
        height: 135,
        reference_rays: 1,
        ..RenderConfig::DEFAULT
    };
    (Scene::bundled("table-and-sphere").expect("bundled"), cfg)
}

fn report(arch: &Arch) -> CostReport {
    let (scene, cfg) = small();
    cfg.check(&scene, &Limits::DEFAULT).and_then(|job| cost(&job, arch)).expect("costs")
}

/// Talisman, then Talisman at twice the clock with twice the bandwidth and
/// half the latency (the same cycles, every rate a cycle alike), then
/// Talisman with DRAM bytes at twice the energy. By hand: the second takes
/// −50 % of the time with the same bytes and energy and ranks first; the
/// third takes the same time (ranked second with the first) and its energy
/// grows by the first's DRAM energy over its total. The table lists them
/// by rank, the time change as 0.500× beside −50 %.
#[test]
fn time_ranks_architectures_of_different_clocks() {
    let a = bundled("talisman");
    let mut b = a.clone();
    for s in ["name=talisman-2x", "clock=150MHz", "dram.bandwidth=2.4GB/s", "dram.latency=25ns"] {
        b.set(s).expect("valid");
    }
    let mut c = a.clone();
    c.set("name=talisman-hot").expect("valid");
    c.set(&format!("energy.dram_byte={}J", 2.0 * a.energy.dram_byte)).expect("valid");
    let reports: Vec<CostReport> = [&a, &b, &c].into_iter().map(report).collect();
    assert!(
        close(reports[0].cycles(), reports[1].cycles()),
        "equal cycles: {} {}",
        reports[0].cycles(),
        reports[1].cycles()
    );
    let cmp = Comparison::new(&reports).expect("three reports");
    assert!(!cmp.one_clock);
    let [first, fast, hot] = [&cmp.archs[0], &cmp.archs[1], &cmp.archs[2]];
    assert_eq!((first.rank, fast.rank, hot.rank), (2, 1, 2));
    assert!(close(fast.seconds_change, -0.5), "{}", fast.seconds_change);
    // Twice the clock: the same dynamic energy, half the leakage.
    let e = &reports[0].energy();
    assert!(fast.dram_bytes_change == 0.0 && close(fast.energy_change, -0.5 * e.leakage / e.total()), "{fast:?}");
    assert!(close(hot.energy_change, e.dram / e.total()), "{} against {}", hot.energy_change, e.dram / e.total());
    assert!(close(hot.seconds_change, 0.0) && hot.dram_bytes_change == 0.0);
    let md = cmp.markdown();
    assert!(md.contains("the clocks differ, so time ranks, not cycles"), "{md}");
    // Ranked rows, fastest first, each change a ratio beside its percent.
    let ranks: Vec<&str> =
        md.lines().filter(|l| l.starts_with("| ") && !l.starts_with("| rank")).map(|l| &l[2..3]).collect();
    assert_eq!(ranks, ["1", "2", "2"], "{md}");
    assert!(
        md.lines().any(|l| l.starts_with("| 1 | talisman-2x | 150 |") && l.contains("| 0.500× (-50.0 %) |")),
        "{md}"
    );
    assert!(Comparison::new(&reports[..1]).is_none(), "one architecture compares with nothing");
}

/// The bottleneck of a stats file's code: its place in the legend.
fn codes_of(code: f64) -> Bottleneck {
    Bottleneck::ALL.into_iter().chain([Bottleneck::Nothing]).nth(code as usize).expect("a code in the legend")
}

/// The unit each kind of figure must carry, by the end of its name.
const UNITS: [(&str, &str); 24] = [
    ("frame.cycles", "cycles"),
    ("frame.seconds", "s"),
    ("frame.frames_per_second", "1/s"),
    ("frame.dram_bytes", "B"),
    ("frame.dram.achieved_bytes_per_second", "B/s"),
    ("frame.dram.peak_bytes_per_second", "B/s"),
    ("frame.dram.latency_ceiling_bytes_per_second", "B/s"),
    ("frame.energy.dram_joules", "J"),
    ("frame.energy.total_joules", "J"),
    ("light.memory.latency_cycles", "cycles"),
    ("light.bound.dram_latency", "count"),
    ("light.bound.map_cache_misses_in_flight", "count"),
    ("camera.memory.map_cache_misses_cycles", "cycles"),
    ("frame.bottleneck", "code"),
    ("light.depth_cache.hits", "count"),
    ("light.depth_cache.hit_rate", "ratio"),
    ("light.depth_cache.written_back_bytes", "B"),
    ("camera.map_cache.fetched_bytes", "B"),
    ("camera.stage.memory_cycles", "cycles"),
    ("light.events.tile_load_bytes", "B"),
    ("light.events.submitted", "count"),
    ("sen.map_bytes_per_pixel", "B/px"),
    ("sen.volume_bytes_per_fragment", "B/fragment"),
    ("sen.p_fill_ratio", "ratio"),
];

/// The stats file of a render on a machine with both caches: every value
/// line `name value # description (unit)` with a number; units as the
/// table says; no name twice; the caches' statistics consistent with the
/// DRAM bytes by purpose; the bottlenecks codes the header's legend
/// names.
#[test]
fn the_stats_file_has_one_convention() {
    let r = report(&bundled("desktop-imr"));
    let text = r.stats("umbra cost --arch desktop-imr");
    let (stats, rest) = text.split_once("---------- End Simulation Statistics").expect("the stats section ends");
    let mut values: HashMap<&str, (f64, &str)> = HashMap::new();
    for line in stats.lines().skip(1).filter(|l| !l.starts_with('#')) {
        let (figure, comment) = line.split_once(" # ").unwrap_or_else(|| panic!("no description: {line}"));
        let mut words = figure.split_whitespace();
        let (name, value) = (words.next().expect("a name"), words.next().expect("a value"));
        assert!(words.next().is_none(), "{line}");
        let value: f64 = value.parse().unwrap_or_else(|_| panic!("not a number: {line}"));
        let unit = comment.rsplit_once(" (").and_then(|(_, u)| u.strip_suffix(')')).expect("a unit");
        assert!(values.insert(name, (value, unit)).is_none(), "{name} twice");
        for (word, want) in [("bytes", "B"), ("joules", "J"), ("seconds", "s"), ("cycles", "cycles")] {
            if name.rsplit('.').next().is_some_and(|last| last.ends_with(word)) {
                assert!(unit.starts_with(want) || unit.ends_with(&format!("/{want}")), "{line}");
            }
        }
    }
    for (name, unit) in UNITS {
        let got = values.get(name).unwrap_or_else(|| panic!("{name} missing"));
        assert_eq!(got.1, unit, "{name}");
    }
    let v = |name: &str| values[name].0;
    assert!(close(v("frame.dram_bytes"), v("light.dram_bytes") + v("camera.dram_bytes")));
    for pass in ["light", "camera"] {
        let c = |k: &str| v(&format!("{pass}.depth_cache.{k}"));
        // Rates are written to 7 significant digits.
        let rate = c("hits") / c("accesses");
        assert!(close(c("accesses"), c("hits") + c("misses")) && (c("hit_rate") - rate).abs() < 1e-6 * rate);
        let rmw = v(&format!("{pass}.dram.off_chip_depth_bytes"));
        assert!(
            close(c("fetched_bytes") + c("written_back_bytes"), rmw),
            "{pass}: the depth cache's lines are its DRAM bytes"
        );
    }
    assert!(close(v("camera.map_cache.fetched_bytes"), v("camera.dram.map_cache_fills_bytes")));
    assert!(!values.contains_key("light.map_cache.accesses"), "the light pass reads no map");
    let legend = text.lines().find_map(|l| l.strip_prefix("# bottleneck codes: ")).expect("the codes' legend");
    let codes: Vec<String> =
        Bottleneck::ALL.iter().chain([&Bottleneck::Nothing]).enumerate().map(|(k, b)| format!("{k} {b}")).collect();
    assert_eq!(legend, codes.join(", "));
    let bottlenecks: Vec<(&str, Bottleneck)> = ["light.bottleneck", "camera.bottleneck", "frame.bottleneck"]
        .into_iter()
        .map(|name| (name, codes_of(values[name].0)))
        .collect();
    assert_eq!(rest.trim(), "----------", "every statistic in the one section");
    // The frame's: what bounds the most of both passes' cycles.
    let frame: Vec<f64> = (0..9).map(|k| r.light.bound_cycles[k] + r.camera.bound_cycles[k]).collect();
    let most = (0..9).fold(0, |b, k| if frame[k] > frame[b] { k } else { b });
    assert_eq!(bottlenecks[2].1, Bottleneck::ALL[most]);
    assert_eq!((bottlenecks[0].1, bottlenecks[1].1), (r.light.bottleneck(), r.camera.bottleneck()));
    // The row's figures are the stats file's, each declared once: the
    // frame's cycles rounded as the row rounds them (half away from zero),
    // the passes' culling in percent, to the file's 7 digits.
    assert_eq!(v("frame.cycles"), r.cycles().round(), "{}", r.cycles());
    let culled = 100.0 * r.max_z_cull_rate[0];
    assert!((v("light.max_z_culled_percent") - culled).abs() <= 1e-6 * culled, "{culled}");
}

/// `cost.json` holds each report's statistics as its stats file lists
/// them: every line's name, with the value the line prints (to its 7
/// digits; a bottleneck's name for its code) and the same unit, and
/// nothing else.
#[test]
fn cost_json_holds_the_stats_files_statistics() {
    let r = report(&bundled("desktop-imr"));
    let dir = crate::common::scratch("cost-json");
    let mut folder = OutputFolder::create(
        &dir.join("out"),
        umbra::sim::output::folder::Claim::new(umbra::sim::output::folder::RunKind::Cost),
    )
    .expect("a folder");
    write_costs(&mut folder, std::slice::from_ref(&r)).expect("written");
    folder.finish(None).expect("finished");
    let stats = std::fs::read_to_string(dir.join("out/stats-desktop-imr.txt")).expect("the stats file");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/cost.json")).expect("cost.json")).expect("JSON");
    let listed = json["statistics"][0].as_object().expect("the report's statistics");
    let mut lines = 0;
    for line in stats.lines().filter(|l| !l.starts_with('#') && l.contains(" # ")) {
        let (figure, comment) = line.split_once(" # ").expect("a description");
        let mut words = figure.split_whitespace();
        let (name, text) = (words.next().expect("a name"), words.next().expect("a value"));
        let s = listed.get(name).unwrap_or_else(|| panic!("{name} is not in cost.json"));
        let x: f64 = text.parse().unwrap_or_else(|_| panic!("not a number: {line}"));
        assert!(comment.ends_with(&format!("({})", s["unit"].as_str().expect("a unit"))), "{line}");
        match s["value"].as_str() {
            // A bottleneck: its name in cost.json, its code in the file.
            Some(b) => assert_eq!(codes_of(x).name(), b, "{name}"),
            None => {
                let y = s["value"].as_f64().expect("a number");
                assert!((x - y).abs() <= 1e-6 * y.abs(), "{name}: {x} against {y}");
            }
        }
        lines += 1;
    }
    assert_eq!(lines, listed.len(), "cost.json lists what the stats file does, no more");
    assert_eq!(listed["frame.cycles"]["value"], r.cycles().round(), "the frame's whole cycles");
    let _ = std::fs::remove_dir_all(&dir);
}
