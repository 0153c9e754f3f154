//! What the simulator reads in: the limits every input is read within
//! ([`limits`]), and fixed-length arrays read exactly (`exact`).

pub(crate) mod exact;
pub mod limits;
