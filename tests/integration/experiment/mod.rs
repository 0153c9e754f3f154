//! The planner and the study: sweeps, shards and merges.

mod plan;
mod study;
