//! The planner and the study's sweep files and requests (the study's
//! runs, shards, merges and summary are tested beside them, in
//! `sim/src/experiment/study/tests/`).

mod plan;
mod request;
mod sweeps;
