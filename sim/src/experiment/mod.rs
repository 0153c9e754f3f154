//! Experiments over renders: the planner (a configuration for an error
//! budget) and the study (a sweep of configurations, its summary and plots).

pub mod correlation;
pub mod plan;
pub mod presets;
pub mod study;
