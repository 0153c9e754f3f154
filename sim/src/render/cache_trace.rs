//! The map cache against an independent cache simulator: the camera pass's
//! texel addresses, as the map cache sees them, recorded for three renders
//! (first depth with bilinear, second depth, a silhouette map) and fed to
//! `pycachesim` (an LRU set-associative simulator) for every map cache
//! geometry of the bundled architectures and a sweep of sizes; its hits
//! and misses must be the costing's exactly.
//!
//! `pycachesim` keeps 32 bits of an address (it counts a load of 2³² as a
//! hit on 0), and the map cache puts a silhouette map at 2⁴⁰, above the
//! depths: the trace it is fed moves that bit to bit 31, which changes no
//! set and no tag of these maps (every other address is below 2³¹).
//!
//! Needs Python with `pycachesim` (`pip install pycachesim==0.3.1`):
//! `.ci/run` installs it in its venv and runs this test with
//! `UMBRA_PYTHON` naming that Python.

use umbra_core::probe::{Event, TexelRead, Tilings};
use umbra_core::{D24, Probe};

use super::costed::reading;
use super::{RenderConfig, passes};
use crate::cost::arch::{Arch, BUNDLED};
use crate::cost::timing::{ArchProbe, PassKind};
use crate::input::limits::Limits;
use crate::pass::algorithm::Algorithm;
use crate::render::cost;
use crate::world::scene::Scene;
use umbra_core::shadow::Filter;
use umbra_core::{DepthFormatKind, NoProbe};

/// A camera probe that records each texel read's address in the map
/// cache's address space, as the costing's map cache computes it.
struct Recorder {
    probe: ArchProbe,
    addresses: Vec<u64>,
}

impl Probe for Recorder {
    const TEXELS: bool = true;

    fn event(&mut self, _: Event) {}

    fn texel_read(&mut self, r: TexelRead) {
        if let (_, _, Some(m)) = self.probe.tallied_as() {
            self.addresses.push(m.address(r));
        }
    }

    fn texel_read_for(&mut self, tilings: Tilings, r: TexelRead) {
        if tilings.has(0) {
            self.texel_read(r);
        }
    }

    fn map_bound(&mut self, light: u16) {
        self.probe.map_bound(light);
    }
}

/// The map-cache addresses of `cfg`'s camera pass of `scene` on `arch`.
fn trace(scene: &Scene, cfg: &RenderConfig, arch: &Arch) -> Vec<u64> {
    let job = cfg.check(scene, &Limits::DEFAULT).expect("a valid configuration");
    let checked = job.targets(arch.tiling().tile).expect("targets");
    let units = cfg.algorithm.units::<D24>(cfg.bias);
    let probe =
        reading(ArchProbe::new(arch, PassKind::Camera, checked.image, DepthFormatKind::D24, 1), cfg, &units, true);
    let mut recorder = Recorder { probe, addresses: Vec::new() };
    let slots = super::map_slots(scene, cfg, checked.map).expect("maps");
    let lights = vec![NoProbe; slots.len()];
    let lit = crate::world::occluders::Lit::each(scene);
    passes::<D24, _, _>((scene, &lit), cfg, (checked, &slots), &mut Vec::new(), lights, &mut recorder, arch.tiling())
        .expect("renders");
    recorder.addresses
}

/// The bit of a silhouette map's addresses in the map cache's address space.
const SILHOUETTE_BIT: u64 = crate::cost::cache::SILHOUETTE_BASE;
const _: () = assert!(SILHOUETTE_BIT.is_power_of_two(), "one bit marks a silhouette map");

/// What `pycachesim` says of `trace` through each of `geometries` (size,
/// line, ways) under `policy`: hits and misses.
fn pycachesim(python: &str, trace: &[u64], geometries: &[(u64, u64, u64)], policy: &str) -> Vec<(u64, u64)> {
    let dir = std::env::temp_dir().join(format!("umbra-cache-trace-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let file = dir.join("trace.bin");
    let below = |a: u64| a & !SILHOUETTE_BIT;
    assert!(trace.iter().all(|&a| below(a) < 1 << 31), "every address fits 31 bits besides the silhouette's");
    let thirty_two = trace.iter().map(|&a| below(a) | if a & SILHOUETTE_BIT != 0 { 1 << 31 } else { 0 });
    std::fs::write(&file, thirty_two.flat_map(u64::to_le_bytes).collect::<Vec<u8>>()).expect("written");
    let script = r#"
import struct, sys
from cachesim import CacheSimulator, Cache, MainMemory
data = open(sys.argv[1], "rb").read()
trace = struct.unpack("<%dQ" % (len(data) // 8), data)
policy = sys.argv[2]
for g in sys.argv[3:]:
    size, line, ways = map(int, g.split(","))
    l1 = Cache("L1", size // (line * ways), ways, line, policy)
    mem = MainMemory()
    mem.load_to(l1)
    mem.store_from(l1)
    cs = CacheSimulator(l1, mem)
    for a in trace:
        cs.load(a, 1)
    print(l1.backend.HIT_count, l1.backend.MISS_count)
"#;
    let out = std::process::Command::new(python)
        .arg("-c")
        .arg(script)
        .arg(&file)
        .arg(policy)
        .args(geometries.iter().map(|(s, l, w)| format!("{s},{l},{w}")))
        .output()
        .expect("Python runs");
    let _ = std::fs::remove_dir_all(&dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| {
            let mut n = l.split_whitespace().map(|x| x.parse::<u64>().expect("a count"));
            (n.next().expect("hits"), n.next().expect("misses"))
        })
        .collect()
}

#[test]
#[ignore = "needs Python with pycachesim, named by UMBRA_PYTHON: .ci/run installs both and runs it"]
fn the_map_cache_is_pycachesim_s_lru_cache() {
    let python = std::env::var("UMBRA_PYTHON").expect("UMBRA_PYTHON names a Python with pycachesim");
    let limits = Limits::DEFAULT;
    let scene = Scene::open("table-and-sphere", &limits).expect("bundled");
    let talisman = Arch::open("talisman", &limits).expect("bundled");
    // Every bundled machine's map cache, and a sweep of sizes and ways.
    let mut geometries: Vec<(u64, u64, u64)> = BUNDLED
        .iter()
        .map(|(name, _)| Arch::open(name, &limits).expect("bundled").map_cache)
        .filter(|c| c.size > 0)
        .map(|c| (c.size, c.line, c.ways))
        .collect();
    for size in [4096, 16384, 65536, 262_144] {
        for ways in [1, 4, 16] {
            geometries.push((size, 64, ways));
        }
    }
    geometries.sort_unstable();
    geometries.dedup();
    let base = RenderConfig { width: 240, height: 135, map_size: 256, reference_rays: 1, ..RenderConfig::DEFAULT };
    let configs = [
        RenderConfig { algorithm: Algorithm::First, filter: Filter::Bilinear, ..base },
        RenderConfig { algorithm: Algorithm::Second, ..base },
        RenderConfig { algorithm: Algorithm::Silhouette { packed: false }, ..base },
    ];
    let mut lru_differs_from_fifo = false;
    for cfg in &configs {
        let addresses = trace(&scene, cfg, &talisman);
        assert!(addresses.len() > 1000, "{}: {} reads", cfg.describe(), addresses.len());
        let theirs = pycachesim(&python, &addresses, &geometries, "LRU");
        let fifo = pycachesim(&python, &addresses, &geometries, "FIFO");
        for ((size, line, ways), (&(hits, misses), &other)) in geometries.iter().zip(theirs.iter().zip(&fifo)) {
            let mut arch = talisman.clone();
            for set in
                [format!("map_cache.size={size}B"), format!("map_cache.line={line}B"), format!("map_cache.ways={ways}")]
            {
                arch.set(&set).expect("a geometry");
            }
            let r = cost(&cfg.check(&scene, &limits).expect("valid"), &arch).expect("costs");
            let ours = r.camera.map_cache.expect("a map cache");
            let what = format!("{}, {size} B, {line} B lines, {ways} ways", cfg.describe());
            assert_eq!((ours.hits, ours.misses), (hits, misses), "{what}");
            lru_differs_from_fifo |= other != (hits, misses);
        }
    }
    // The comparison can tell replacement policies apart.
    assert!(lru_differs_from_fifo, "FIFO would have passed too");
}
