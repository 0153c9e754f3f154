//! The Cortex-M firmware (`hosts/cortex-m`) under QEMU, on three boards —
//! the Cortex-M4F of MPS2-AN386, the Cortex-M3 of the LM3S6965 and the
//! Cortex-M0 of the micro:bit — renders the demo scene bit for bit as the
//! host does: the same map and camera checksums, the same event totals
//! (on the boards built with the counters); and stays within each board's
//! memory budget, its measured peak stack included. And the host's demo agrees with the simulator's own light
//! pass and event counters.
//!
//! Without `qemu-system-arm` or a target the firmware test is skipped with
//! a notice, unless `CI=true`.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use object::{Object, ObjectSection};
use umbra::core::D16;
use umbra::core::probe::Totals;
use umbra::sim::base::counters::Counters;
use umbra::sim::pass::light::{Draw, LightFrame, LightOptions, render};
use umbra_demo::footprint::{self, CameraFootprint, FootprintConfig};
use umbra_demo::{BIN_CAPACITY, Full, SETUPS, Small, Summary, scene};

/// Far more than the firmware needs (seconds).
const QEMU_TIMEOUT: Duration = Duration::from_secs(120);

/// A board the firmware runs on, and the budget it must keep.
struct Board {
    target: &'static str,
    machine: &'static [&'static str],
    /// The demo variant its RAM holds: the full one, or the small one.
    small: bool,
    /// Whether its firmware is built with the event counters.
    counted: bool,
    /// RAM the firmware may use, statics and peak stack together.
    ram: u64,
    /// Flash the firmware may use (vector table, code, read-only data and
    /// the image of initialised data).
    flash: u64,
}

const BOARDS: [Board; 3] = [
    Board {
        target: "thumbv7em-none-eabihf",
        machine: &["-machine", "mps2-an386", "-cpu", "cortex-m4"],
        small: false,
        counted: true,
        ram: 4 << 20,
        flash: 512 << 10,
    },
    // The budget of the issue that set it: 32 KiB of the part's 64 KiB of
    // SRAM and 64 KiB of its 256 KiB of flash (which leaves the event
    // counters out).
    Board {
        target: "thumbv7m-none-eabi",
        machine: &["-machine", "lm3s6965evb", "-cpu", "cortex-m3"],
        small: false,
        counted: false,
        ram: 32 << 10,
        flash: 64 << 10,
    },
    Board {
        target: "thumbv6m-none-eabi",
        machine: &["-machine", "microbit"],
        small: true,
        counted: true,
        ram: 16 << 10,
        flash: 256 << 10,
    },
];

fn firmware_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("hosts/cortex-m")
}

/// Why the firmware cannot be run here for `target`, if it cannot.
fn missing_tools(target: &str) -> Option<String> {
    let qemu = Command::new("qemu-system-arm").arg("--version").stdout(Stdio::null()).stderr(Stdio::null()).status();
    if !qemu.is_ok_and(|s| s.success()) {
        return Some("qemu-system-arm is not installed".into());
    }
    let sysroot = Command::new(option_env!("RUSTC").unwrap_or("rustc")).args(["--print", "sysroot"]).output();
    let has_target = sysroot.is_ok_and(|o| {
        let root = String::from_utf8_lossy(&o.stdout).trim().to_owned();
        Path::new(&root).join("lib/rustlib").join(target).is_dir()
    });
    (!has_target).then(|| format!("the {target} target is not installed (rustup target add {target})"))
}

/// Build the firmware for `target` in its own workspace and target directory.
fn build_firmware(target: &str) -> PathBuf {
    let dir = firmware_dir();
    let mut cargo = Command::new(option_env!("CARGO").unwrap_or("cargo"));
    cargo
        .args(["build", "--release", "--quiet", "--target", target])
        .current_dir(&dir)
        // The firmware's own `.cargo/config.toml` and profile decide flags
        // and runners, whatever the environment overrides for the host.
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("CARGO_BUILD_TARGET")
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS");
    for (key, _) in std::env::vars_os() {
        if key.to_string_lossy().starts_with("CARGO_PROFILE_") {
            cargo.env_remove(key);
        }
    }
    let out = cargo.output().expect("cargo runs");
    assert!(out.status.success(), "firmware build for {target} failed:\n{}", String::from_utf8_lossy(&out.stderr));
    dir.join("target").join(target).join("release/umbra-cortex-m")
}

/// Run the firmware under QEMU on `board`: its exit status and its
/// `key=value` lines.
fn run_firmware(board: &Board, elf: &Path) -> (i32, BTreeMap<String, String>) {
    let mut child = Command::new("qemu-system-arm")
        .args(board.machine)
        .args(["-nographic", "-semihosting-config", "enable=on,target=native", "-icount", "shift=0", "-kernel"])
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
            panic!("the firmware did not exit within {QEMU_TIMEOUT:?} on {}", board.target);
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let text = reader.join().expect("reader thread").expect("qemu output is UTF-8");
    let lines =
        text.lines().filter_map(|l| l.trim().split_once('=')).map(|(k, v)| (k.to_owned(), v.to_owned())).collect();
    (status.code().unwrap_or(-1), lines)
}

/// What the firmware must print for this summary and these totals.
fn expected_lines(s: &Summary, (light, camera): (&Totals, &Totals)) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    m.insert("map_checksum".to_owned(), format!("{:#018x}", s.map_checksum));
    m.insert("camera_checksum".to_owned(), format!("{:#018x}", s.camera_checksum));
    m.insert("covered".to_owned(), s.covered.to_string());
    m.insert("shadowed".to_owned(), s.shadowed.to_string());
    for (pass, totals) in [("light", light), ("camera", camera)] {
        for (name, value) in totals.fields() {
            m.insert(format!("{pass}.{name}"), value.to_string());
        }
    }
    m
}

/// The host's render of a variant: what the firmware must print, and the
/// variant's map side and setup count.
fn host_lines(small: bool) -> (BTreeMap<String, String>, u32, usize) {
    if small {
        let mut mem = Box::new(Small::new());
        let s = umbra_demo::render(&mut mem).expect("the demo renders");
        (expected_lines(&s, mem.totals()), Small::MAP_SIDE, Small::SETUPS)
    } else {
        let mut mem = Box::new(Full::new());
        let s = umbra_demo::render(&mut mem).expect("the demo renders");
        (expected_lines(&s, mem.totals()), Full::MAP_SIDE, Full::SETUPS)
    }
}

/// The ELF's allocated sections: `(flash, statics)` bytes — flash holds
/// the vector table, code, read-only data and the image of `.data`; RAM
/// holds `.data` and `.bss`.
fn sections(elf: &Path) -> (u64, u64) {
    let bytes = std::fs::read(elf).expect("the firmware's ELF");
    let file = object::File::parse(&*bytes).expect("an ELF file");
    let size = |name: &str| file.section_by_name(name).map_or(0, |s| s.size());
    let flash = size(".vector_table") + size(".text") + size(".rodata") + size(".data");
    (flash, size(".data") + size(".bss"))
}

#[test]
#[ignore = "needs qemu-system-arm and the thumbv6m, thumbv7m and thumbv7em targets (docs/firmware.md): run with `cargo test --test integration firmware -- --ignored`"]
fn firmware_under_qemu_matches_the_host_within_budget() {
    for board in &BOARDS {
        if let Some(why) = missing_tools(board.target) {
            panic!("firmware on {}: {why}", board.target);
        }
        let elf = build_firmware(board.target);
        let (status, got) = run_firmware(board, &elf);
        let t = board.target;
        assert_eq!(status, 0, "{t}: firmware exit status; output: {got:?}");
        let (want, side, setups) = host_lines(board.small);
        for (key, want) in want {
            let total = key.starts_with("light.") || key.starts_with("camera.");
            let want = (board.counted || !total).then_some(want);
            assert_eq!(got.get(&key), want.as_ref(), "{t}: {key}: firmware vs host");
        }
        // The footprint formulas, evaluated on the target, equal the sizes
        // of the buffer types there, and what the host computes for a
        // 32-bit target.
        let number =
            |key: &str| got.get(key).and_then(|v| v.parse::<u64>().ok()).unwrap_or_else(|| panic!("{t}: {key}"));
        assert_eq!(number("light_ram_formula"), number("light_ram_types"), "{t}");
        assert_eq!(number("camera_ram_formula"), number("camera_ram_types"), "{t}");
        let light = FootprintConfig { pointer_bytes: 4, ..umbra_demo::light_footprint_config(side, setups) };
        assert_eq!(number("light_ram_types"), footprint::light_pass(&light).unwrap().total() as u64, "{t}");
        let camera = CameraFootprint { pointer_bytes: 4, ..umbra_demo::camera_footprint_config() };
        assert_eq!(number("camera_ram_types"), footprint::camera_pass(&camera).unwrap().total() as u64, "{t}");
        // The budget: statics and the measured peak stack within the RAM
        // budget, the stack inside its region (a stack that reached the
        // statics would have overwritten them), the image within flash.
        let (flash, statics) = sections(&elf);
        let (peak, region) = (number("stack_peak"), number("stack_region"));
        assert!(peak < region, "{t}: the stack reached the statics ({peak} of {region} bytes)");
        assert!(statics + peak <= board.ram, "{t}: {statics} B of statics + {peak} B of stack > {} B", board.ram);
        assert!(flash <= board.flash, "{t}: {flash} B of flash > {} B", board.flash);
        // Each pass's instructions, from SysTick under `-icount shift=0`:
        // some, and the light pass of 62 triangles fewer than the camera
        // pass that sends them once per tile of 64.
        let (light, camera) = (number("light_instructions"), number("camera_instructions"));
        assert!(light > 100_000 && camera > 10 * light, "{t}: {light} and {camera} instructions");
        eprintln!("{t}: light pass {light} instructions, camera pass {camera}; {statics} B statics, {peak} B stack");
    }
}

/// The demo's light pass through the core directly gives the maps and the
/// event totals the simulator's own light pass and counters give.
#[test]
fn host_demo_matches_the_simulator() {
    let mut mem = Box::new(Full::new());
    let s = umbra_demo::render(&mut mem).expect("the demo renders");
    let cfg = umbra_demo::light_config(Full::MAP_SIDE).unwrap();
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
    assert_eq!(*mem.totals().0, counters.totals);
    assert!(counters.totals.flushes_setup_full > 0, "the small setup store fills at least once");
    // The demo's map checksum is FNV-1a 64 over z1 then z2 as little-endian u16.
    let mut bytes = Vec::new();
    maps.z1.iter().chain(&maps.z2).for_each(|t| bytes.extend_from_slice(&t.to_le_bytes()));
    let mut h = umbra_demo::Fnv1a::new();
    h.bytes(&bytes);
    assert_eq!(s.map_checksum, h.finish());
}
