//! The exact f64 reference and the metrics of a render against it.

pub mod metrics;
pub mod reference;
