//! Named configurations the benches and the study sweep.

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
