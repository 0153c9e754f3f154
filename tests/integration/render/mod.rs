//! One render's configuration: its parameters and its one check.

mod lights;
mod params;
mod pictures;
