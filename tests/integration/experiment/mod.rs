//! The planner and the study: sweeps, sweep files, shards, merges and the
//! summary.

mod merge;
mod plan;
mod request;
mod shared;
mod study;
mod summary;
mod sweeps;
