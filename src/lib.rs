#![forbid(unsafe_code)]
//! Umbra: a bit-exact, cycle-counting model of fixed-function shadow-mapping
//! hardware. This facade re-exports the hardware ([`core`]) and the
//! simulator around it ([`sim`]); it owns the integration tests and benches.

pub use umbra_core as core;
pub use umbra_sim as sim;
