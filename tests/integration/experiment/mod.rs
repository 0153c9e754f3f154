//! The planner and the study: sweeps, sweep files, shards, merges and the
//! summary.

mod merge;
mod plan;
mod shared;
mod study;
mod summary;
mod sweeps;
