//! One render's configuration: its parameters and its one check.

mod params;
mod pictures;
