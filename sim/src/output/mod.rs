//! What the simulator writes out: output folders ([`folder`]), the formats
//! maps and pictures are written in ([`formats`]), text broken into lines
//! ([`lines`]), Markdown text ([`markdown`]), pictures framed to explain themselves ([`picture`]), every table in Markdown or CSV ([`table`]), where an output came from ([`provenance`]), and why a
//! file could not be written (`OutputError`).

mod error;
pub mod folder;
pub mod formats;
pub mod lines;
pub mod markdown;
pub mod picture;
pub mod provenance;
pub mod table;

pub use error::OutputError;
