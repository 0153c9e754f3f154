//! Architecture files: the machine a render is costed on ([`Arch`]), its
//! keys and units, the bundled presets, and what a file implies
//! ([`derived`]).

pub mod derived;
pub mod file;
mod keys;
mod machine;
mod presets;
mod units;

pub use file::ArchError;
pub use keys::{Problem, Unit};
pub use machine::{Arch, Calibration};
pub use units::CacheParams;
