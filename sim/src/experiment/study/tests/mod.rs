//! The study's runs, shards, merges and summary, tested beside the
//! internals they need (writing a run, reading its manifest, the render
//! every configuration would have without sharing).

mod merge;
mod shared;
mod study;
mod summary;
mod tallies;
