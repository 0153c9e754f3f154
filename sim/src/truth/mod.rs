//! The exact f64 reference and the metrics of a render against it.

pub mod cause;
pub mod metrics;
pub mod reference;
