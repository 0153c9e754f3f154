//! One render's configuration: its parameters and its one check.

mod cascades;
mod lights;
mod params;
mod pictures;
