//! The Cortex-M firmware (`hosts/cortex-m`) under QEMU renders the demo
//! scene bit for bit as the host does: the same map and camera checksums,
//! the same event totals. And the host's demo agrees with the simulator's
//! own light pass and event counters.
//!
//! Without `qemu-system-arm` or the `thumbv7em-none-eabihf` target the
//! firmware test is skipped with a notice, unless `CI=true`.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use umbra::core::D16;
use umbra::sim::cost::counters::Counters;
use umbra::sim::pass::light::{Draw, LightFrame, LightOptions, render};
use umbra_demo::footprint::{self, FootprintConfig};
use umbra_demo::{BIN_CAPACITY, Memory, SETUPS, Summary, scene};

const TARGET: &str = "thumbv7em-none-eabihf";
/// Far more than the firmware needs (a fraction of a second).
const QEMU_TIMEOUT: Duration = Duration::from_secs(120);

fn firmware_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("hosts/cortex-m")
}

/// Why the firmware cannot be run here, if it cannot.
fn missing_tools() -> Option<String> {
    let qemu = Command::new("qemu-system-arm").arg("--version").stdout(Stdio::null()).stderr(Stdio::null()).status();
    if !qemu.is_ok_and(|s| s.success()) {
        return Some("qemu-system-arm is not installed".into());
    }
    let sysroot = Command::new(option_env!("RUSTC").unwrap_or("rustc")).args(["--print", "sysroot"]).output();
    let has_target = sysroot.is_ok_and(|o| {
        let root = String::from_utf8_lossy(&o.stdout).trim().to_owned();
        Path::new(&root).join("lib/rustlib").join(TARGET).is_dir()
    });
    (!has_target).then(|| format!("the {TARGET} target is not installed (rustup target add {TARGET})"))
}

/// Build the firmware in its own workspace and target directory.
fn build_firmware() -> PathBuf {
    let dir = firmware_dir();
    let out = Command::new(option_env!("CARGO").unwrap_or("cargo"))
        .args(["build", "--release", "--quiet"])
        .current_dir(&dir)
        // The firmware's own `.cargo/config.toml` decides target and flags.
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("CARGO_BUILD_TARGET")
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .output()
        .expect("cargo runs");
    assert!(out.status.success(), "firmware build failed:\n{}", String::from_utf8_lossy(&out.stderr));
    dir.join("target").join(TARGET).join("release/umbra-cortex-m")
}

/// Run the firmware under QEMU: its exit status and its `key=value` lines.
fn run_firmware(elf: &Path) -> (i32, BTreeMap<String, String>) {
    let mut child = Command::new("qemu-system-arm")
        .args(["-machine", "mps2-an386", "-cpu", "cortex-m4", "-nographic"])
        .args(["-semihosting-config", "enable=on,target=native", "-kernel"])
        .arg(elf)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .expect("qemu-system-arm starts");
    let mut stdout = child.stdout.take().expect("piped stdout");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        stdout.read_to_string(&mut s).map(|_| s)
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("qemu can be waited for") {
            break status;
        }
        if start.elapsed() > QEMU_TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            panic!("the firmware did not exit within {QEMU_TIMEOUT:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let text = reader.join().expect("reader thread").expect("qemu output is UTF-8");
    let lines =
        text.lines().filter_map(|l| l.trim().split_once('=')).map(|(k, v)| (k.to_owned(), v.to_owned())).collect();
    (status.code().unwrap_or(-1), lines)
}

/// What the firmware must print for this summary.
fn expected_lines(s: &Summary) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    m.insert("map_checksum".to_owned(), format!("{:#018x}", s.map_checksum));
    m.insert("camera_checksum".to_owned(), format!("{:#018x}", s.camera_checksum));
    m.insert("covered".to_owned(), s.covered.to_string());
    m.insert("shadowed".to_owned(), s.shadowed.to_string());
    for (pass, totals) in [("light", &s.light), ("camera", &s.camera)] {
        for (name, value) in totals.fields() {
            m.insert(format!("{pass}.{name}"), value.to_string());
        }
    }
    m
}

fn host_summary() -> (Summary, Box<Memory>) {
    let mut mem = Box::new(Memory::new());
    let s = umbra_demo::render(&mut mem).expect("the demo renders");
    (s, mem)
}

#[test]
fn firmware_under_qemu_matches_the_host() {
    if let Some(why) = missing_tools() {
        assert!(std::env::var("CI").as_deref() != Ok("true"), "CI=true but {why}");
        eprintln!("SKIPPED firmware_under_qemu_matches_the_host: {why}");
        return;
    }
    let elf = build_firmware();
    let (status, got) = run_firmware(&elf);
    assert_eq!(status, 0, "firmware exit status; output: {got:?}");
    let (host, _) = host_summary();
    for (key, want) in expected_lines(&host) {
        assert_eq!(got.get(&key), Some(&want), "{key}: firmware vs host");
    }
    // The footprint formula, evaluated on the target, equals the size of the
    // buffer types there, and what the host computes for a 32-bit target.
    let on_target = got.get("light_ram_types").expect("light_ram_types printed");
    assert_eq!(got.get("light_ram_formula"), Some(on_target));
    let cortex_m = FootprintConfig { pointer_bytes: 4, ..umbra_demo::light_footprint_config() };
    assert_eq!(on_target, &footprint::light_pass(&cortex_m).unwrap().total().to_string());
}

/// The demo's light pass through the core directly gives the maps and the
/// event totals the simulator's own light pass and counters give.
#[test]
fn host_demo_matches_the_simulator() {
    let (s, mem) = host_summary();
    let cfg = umbra_demo::light_config().unwrap();
    let draw = Draw {
        positions: &scene::POSITIONS,
        triangles: &scene::INDICES,
        transform: scene::light_matrix(),
        cull: umbra::core::CullMode::None,
    };
    let mut frame = LightFrame::<u16, BIN_CAPACITY>::new();
    let options = LightOptions::with_setups(SETUPS);
    let (maps, counters) =
        render::<D16, Counters, BIN_CAPACITY>(&mut frame, cfg, &[draw], options, Counters::new(&cfg.raster)).unwrap();
    let (z1, z2) = mem.maps();
    assert_eq!(maps.z1, z1);
    assert_eq!(maps.z2, z2);
    // Every total of the demo's pass through the core is the simulator's.
    assert_eq!(s.light, counters.totals);
    assert!(counters.totals.flushes_setup_full > 0, "the small setup store fills at least once");
    // The demo's map checksum is FNV-1a 64 over z1 then z2 as little-endian u16.
    let mut bytes = Vec::new();
    maps.z1.iter().chain(&maps.z2).for_each(|t| bytes.extend_from_slice(&t.to_le_bytes()));
    let mut h = umbra_demo::Fnv1a::new();
    h.bytes(&bytes);
    assert_eq!(s.map_checksum, h.finish());
}
