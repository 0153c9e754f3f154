//! Named configurations the benches and the study sweep.

use umbra_core::shadow::{Filter, Jitter};

/// The filters of the trade study: point, bilinear, 3×3 box, and Reeves'
/// jittered filter with 4 and with 16 samples.
pub const FILTERS: [(&str, Filter); 5] = [
    ("point", Filter::Point),
    ("bilinear", Filter::Bilinear),
    ("box3", Filter::Box { size: 3 }),
    ("jitter4", Filter::Jittered(Jitter { num_samples: 4, ..Jitter::REEVES })),
    ("jitter16", Filter::Jittered(Jitter::REEVES)),
];
