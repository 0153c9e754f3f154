//! The bottom layer: what every other layer shares — the probes that pass
//! events on (`probes`), the event counters ([`counters`]), and raw map
//! formats and tilings ([`maps`]), the one spelling of a typed choice in a
//! file (`text`), and the files this process read and may read
//! ([`reads`]: the inputs read them, the output folders keep them). It
//! imports nothing of the simulator.

pub mod counters;
pub mod maps;
pub(crate) mod probes;
pub mod reads;
pub(crate) mod text;
