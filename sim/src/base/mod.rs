//! The bottom layer: what every other layer shares — the probes that pass
//! events on (`probes`), the event counters ([`counters`]), and raw map
//! formats and tilings ([`maps`]), and the one spelling of a typed choice in a
//! file (`text`). It imports nothing of the simulator.

pub mod counters;
pub mod maps;
pub(crate) mod probes;
pub(crate) mod text;
