//! Named configurations the benches and the study sweep.
//!
//! ```
//! use umbra_sim::experiment::presets::FILTERS;
//! let names: Vec<String> = FILTERS.iter().map(ToString::to_string).collect();
//! assert_eq!(names.len(), 5);
//! // Each reads back from its one spelling.
//! for (f, name) in FILTERS.iter().zip(&names) {
//!     assert_eq!(name.parse::<umbra_sim::core::shadow::Filter>().ok().as_ref(), Some(f));
//! }
//! ```

use umbra_core::shadow::{Filter, Jitter};

/// The filters of the trade study: point, bilinear, 3×3 box, and Reeves'
/// jittered filter with 4 and with 16 samples.
/// Each is named by its one spelling, its `Display`.
pub const FILTERS: [Filter; 5] = [
    Filter::Point,
    Filter::Bilinear,
    Filter::Box { size: 3 },
    Filter::Jittered(Jitter { num_samples: 4, ..Jitter::REEVES }),
    Filter::Jittered(Jitter::REEVES),
];
