//! Pick the memory map of the target's board, put it where the linker
//! (cortex-m-rt's `link.x`) finds it as `memory.x`, and tell the firmware
//! which demo variant the board's RAM holds.

use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").ok_or("OUT_DIR is not set")?);
    let target = std::env::var("TARGET")?;
    // The memory map, the small variant, whether the event counters are
    // built in, and the core clock's period in picoseconds as QEMU models
    // the board (SysTick counts it): MPS2's 25 MHz, the LM3S6965's
    // 12.5 MHz after reset (200 MHz / 16), the nRF51's 16 MHz. The
    // LM3S6965's 64 KiB flash budget has no room for the counters' code.
    let (map, small, counted, clock_ps): (&[u8], bool, bool, u64) = match target.as_str() {
        "thumbv7em-none-eabihf" => (include_bytes!("memory/mps2-an386.x"), false, true, 40_000),
        "thumbv7m-none-eabi" => (include_bytes!("memory/lm3s6965.x"), false, false, 80_000),
        "thumbv6m-none-eabi" => (include_bytes!("memory/nrf51-microbit.x"), true, true, 62_500),
        other => return Err(format!("no board for target {other}").into()),
    };
    std::fs::write(out.join("memory.x"), map)?;
    println!("cargo::rustc-env=UMBRA_CLOCK_PS={clock_ps}");
    println!("cargo::rustc-check-cfg=cfg(small_ram)");
    println!("cargo::rustc-check-cfg=cfg(counted)");
    if small {
        println!("cargo::rustc-cfg=small_ram");
    }
    if counted {
        println!("cargo::rustc-cfg=counted");
    }
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory");
    println!("cargo:rerun-if-changed=build.rs");
    Ok(())
}
