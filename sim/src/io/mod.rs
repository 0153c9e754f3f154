//! Files in and out: the limits every input is read within, and the
//! writers of maps, images and text.

pub mod exact;
pub mod folder;
pub mod limits;
pub mod markdown;
pub mod output;
pub mod provenance;
