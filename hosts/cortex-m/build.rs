//! Pick the memory map of the target's board, put it where the linker
//! (cortex-m-rt's `link.x`) finds it as `memory.x`, and tell the firmware
//! which demo variant the board's RAM holds.

use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").ok_or("OUT_DIR is not set")?);
    let target = std::env::var("TARGET")?;
    let (map, small): (&[u8], bool) = match target.as_str() {
        "thumbv7em-none-eabihf" => (include_bytes!("memory/mps2-an386.x"), false),
        "thumbv7m-none-eabi" => (include_bytes!("memory/lm3s6965.x"), false),
        "thumbv6m-none-eabi" => (include_bytes!("memory/nrf51-microbit.x"), true),
        other => return Err(format!("no board for target {other}").into()),
    };
    std::fs::write(out.join("memory.x"), map)?;
    println!("cargo::rustc-check-cfg=cfg(small_ram)");
    if small {
        println!("cargo::rustc-cfg=small_ram");
    }
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory");
    println!("cargo:rerun-if-changed=build.rs");
    Ok(())
}
