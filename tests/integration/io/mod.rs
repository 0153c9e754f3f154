//! Files in and out: maps as arrays, and hostile inputs to the command.

pub mod folder;
mod hostile;
mod maps_io;
