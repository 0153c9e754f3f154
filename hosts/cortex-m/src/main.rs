//! Umbra's demo scene on a Cortex-M: renders it through `umbra-core` (via
//! `umbra-demo`) in static buffers, the camera pass streamed by tile, and
//! prints the checksums, the event totals and the memory it took as
//! `key=value` lines over semihosting, then exits 0 (1 on an error or a
//! panic). The board's RAM decides the variant: the full demo (64² map)
//! on the Cortex-M4F and the Cortex-M3, a 32² map on the Cortex-M0's
//! 16 KiB. The Cortex-M3's 64 KiB flash budget leaves the event counters
//! out: it renders the same bits uncounted.
#![no_std]
#![no_main]

use core::cell::RefCell;
use core::mem::size_of;

use cortex_m::interrupt::{self, Mutex};
use cortex_m::peripheral::SYST;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use umbra_demo::footprint;

/// The demo variant this board's RAM holds.
#[cfg(not(small_ram))]
type Memory = umbra_demo::Full;
#[cfg(small_ram)]
type Memory = umbra_demo::Small;

/// Every buffer of both passes, zero-initialised in `.bss`.
static MEMORY: Mutex<RefCell<Memory>> = Mutex::new(RefCell::new(Memory::new()));

#[entry]
fn main() -> ! {
    // Paint the free stack, so that its peak use can be read back.
    cortex_m_stack::repaint_stack();
    let status = match cortex_m::Peripherals::take() {
        Some(p) => interrupt::free(|cs| report(&mut MEMORY.borrow(cs).borrow_mut(), p.SYST)),
        None => debug::EXIT_FAILURE,
    };
    debug::exit(status);
    loop {
        cortex_m::asm::wfi();
    }
}

/// Render into `mem` and print what it made; the exit status. SysTick,
/// counting down at the core clock, times each pass: under QEMU's
/// `-icount shift=0` one instruction is one nanosecond of the board's
/// clock, so the ticks count instructions in the board's clock period.
fn report(mem: &mut Memory, mut timer: SYST) -> debug::ExitStatus {
    timer.set_clock_source(SystClkSource::Core);
    timer.set_reload(0x00ff_ffff);
    timer.clear_current();
    timer.enable_counter();
    let start = SYST::get_current();
    let mut light_end = start;
    #[cfg(counted)]
    let rendered = umbra_demo::render_with(mem, || light_end = SYST::get_current());
    #[cfg(not(counted))]
    let rendered = umbra_demo::render_uncounted_with(mem, || light_end = SYST::get_current());
    let end = SYST::get_current();
    match rendered {
        Ok(s) => {
            // A 24-bit down-counter: elapsed ticks modulo 2²⁴ (a pass of
            // more than 2²⁴ ticks would wrap: 0.67 s at 25 MHz).
            let ticks = |from: u32, to: u32| u64::from(from.wrapping_sub(to) & 0x00ff_ffff);
            let clock_ps: u64 = env!("UMBRA_CLOCK_PS").parse().unwrap_or(0);
            for (pass, t) in [("light", ticks(start, light_end)), ("camera", ticks(light_end, end))] {
                line(pass, "_ticks", t);
                // One instruction a nanosecond under `-icount shift=0`.
                line(pass, "_instructions", t * clock_ps / 1000);
            }
            hprintln!("map_checksum={:#018x}", s.map_checksum);
            hprintln!("camera_checksum={:#018x}", s.camera_checksum);
            #[cfg(counted)]
            {
                let (light, camera) = mem.totals();
                print_totals("light.", light);
                print_totals("camera.", camera);
            }
            let side = Memory::MAP_SIDE;
            let light =
                footprint::light_pass(&umbra_demo::light_footprint_config(side, Memory::SETUPS)).map(|f| f.total());
            let camera = footprint::camera_pass(&umbra_demo::camera_footprint_config()).map(|f| f.total());
            let (light_types, camera_types) =
                umbra_demo::buffer_bytes::<{ Memory::MAP_TEXELS }, { Memory::MAP_TILES }, { Memory::SETUPS }>();
            // The stack region runs from the end of the statics to the top
            // of RAM; the part never written since the paint is what the
            // peak (the render and this printing) left.
            let region = cortex_m_stack::stack_size();
            let peak = region.saturating_sub(cortex_m_stack::stack_painted());
            // Sizes on a 32-bit part fit `u32`.
            let bytes = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
            for (key, value) in [
                ("covered", s.covered),
                ("shadowed", s.shadowed),
                ("map_side", side),
                ("light_ram_formula", bytes(light.unwrap_or(0))),
                ("light_ram_types", bytes(light_types)),
                ("camera_ram_formula", bytes(camera.unwrap_or(0))),
                ("camera_ram_types", bytes(camera_types)),
                ("memory_bytes", bytes(size_of::<Memory>())),
                ("stack_region", region),
                ("stack_peak", peak),
            ] {
                line("", key, u64::from(value));
            }
            debug::EXIT_SUCCESS
        }
        Err(e) => {
            hprintln!("error={e}");
            debug::EXIT_FAILURE
        }
    }
}

/// Print `{prefix}{key}={value}`: one formatting site for every line
/// (each site costs flash).
#[inline(never)]
fn line(prefix: &str, key: &str, value: u64) {
    hprintln!("{prefix}{key}={value}");
}

#[cfg(counted)]
/// Print every event total as `{prefix}{name}={value}` (one copy of the
/// field list, for both passes).
#[inline(never)]
fn print_totals(prefix: &str, totals: &umbra_demo::Totals) {
    for (name, value) in totals.fields() {
        line(prefix, name, value);
    }
}

/// A panic prints where it happened (not its message: formatting every
/// message the core could panic with would take flash the budget has
/// not got) and exits with status 1.
#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    match info.location() {
        Some(at) => hprintln!("panic at {}:{}", at.file(), at.line()),
        None => hprintln!("panic"),
    }
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
