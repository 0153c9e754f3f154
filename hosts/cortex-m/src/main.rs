//! Umbra's demo scene on a Cortex-M4F: renders it through `umbra-core`
//! (via `umbra-demo`) in static buffers, prints the checksums and event
//! totals as `key=value` lines over semihosting, and exits 0 (1 on an
//! error or a panic).
#![no_std]
#![no_main]

use core::cell::RefCell;
use core::mem::size_of;

use cortex_m::interrupt::{self, Mutex};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;
use umbra_demo::{Memory, footprint};

/// Every buffer of both passes, zero-initialised in `.bss`.
static MEMORY: Mutex<RefCell<Memory>> = Mutex::new(RefCell::new(Memory::new()));

#[entry]
fn main() -> ! {
    let result = interrupt::free(|cs| umbra_demo::render(&mut MEMORY.borrow(cs).borrow_mut()));
    let status = match result {
        Ok(s) => {
            hprintln!("map_checksum={:#018x}", s.map_checksum);
            hprintln!("camera_checksum={:#018x}", s.camera_checksum);
            hprintln!("covered={}", s.covered);
            hprintln!("shadowed={}", s.shadowed);
            for (pass, totals) in [("light", &s.light), ("camera", &s.camera)] {
                for (name, value) in totals.fields() {
                    hprintln!("{pass}.{name}={value}");
                }
            }
            let predicted = footprint::light_pass(&umbra_demo::light_footprint_config()).map(|f| f.total());
            hprintln!("light_ram_formula={}", predicted.unwrap_or(0));
            hprintln!("light_ram_types={}", umbra_demo::LIGHT_BUFFER_BYTES);
            hprintln!("memory_bytes={}", size_of::<Memory>());
            debug::EXIT_SUCCESS
        }
        Err(e) => {
            hprintln!("error={e}");
            debug::EXIT_FAILURE
        }
    };
    debug::exit(status);
    loop {
        cortex_m::asm::wfi();
    }
}
