//! Architecture files: the machine a render is costed on ([`Arch`]), its
//! keys and units, the bundled presets, what a file implies
//! ([`derived`]), and which keys its units read ([`Arch::unread`]).

pub mod derived;
mod file;
mod keys;
mod machine;
mod measure;
mod presets;
mod reads;
mod units;

pub use file::ArchError;
pub(crate) use keys::column;
pub use keys::{PARAMS, Param, Problem, Value};
pub use machine::{Arch, Calibration};
pub use measure::{NotInUnit, Unit};
pub use presets::BUNDLED;
pub use reads::Unread;
pub use units::{
    Bins, CacheParams, DepthRates, DramParams, Energy, Front, OnChip, Raster, Shade, ShadowRates, Technology,
};
