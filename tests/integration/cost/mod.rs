//! The cost layer: architecture probes, the map cache and the storage schemes, against counts worked by hand.

mod arch;
mod cache;
mod storage;
