//! Experiments over renders: the planner (a configuration for an error
//! budget), the study (a sweep of configurations, its summary and plots),
//! the correlation of the model against measurements, two architectures'
//! difference attributed to their keys, and the plotting they share.

pub mod attribution;
pub mod correlation;
pub mod plan;
pub mod plot;
pub mod presets;
pub mod study;
