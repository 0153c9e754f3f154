//! The bottom layer: what every other layer shares — the probes that pass
//! events on (`probes`), the event counters ([`counters`]), and raw map
//! formats and tilings ([`maps`]), the one spelling of a typed choice in a
//! file (`text`), the files this process read and may read
//! ([`reads`]: the inputs read them, the output folders keep them), and a
//! host's request to stop long work ([`stop`]). It imports nothing of the
//! simulator.

pub mod counters;
pub mod maps;
pub(crate) mod probes;
pub mod reads;
pub mod stop;
pub(crate) mod text;
