//! What a pass costs: the architecture and its timing model, the map
//! cache, the map's storage schemes.

pub mod arch;
pub mod cache;
pub mod storage;
