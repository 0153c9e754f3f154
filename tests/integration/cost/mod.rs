//! The cost layer: architecture probes, the map cache and the storage schemes, against counts worked by hand.

mod arch;
mod arch_file;
mod attribution;
mod bound;
mod cache;
mod correlation;
mod derived;
mod reads;
mod shared;
mod silicon;
mod stack;
mod storage;
