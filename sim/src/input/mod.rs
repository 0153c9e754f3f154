//! What the simulator reads in: the limits every input is read within
//! ([`limits`]), and fixed-length arrays read exactly ([`exact`]).

pub mod exact;
pub mod limits;
