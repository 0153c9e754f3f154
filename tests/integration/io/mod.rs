//! Files in and out: maps as arrays, and hostile inputs to the command.

mod hostile;
mod maps_io;
