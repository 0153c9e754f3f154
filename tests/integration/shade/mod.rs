//! The camera pass's shading unit against an f64 evaluation of the same pixels.

mod blocks;
mod camera_pass;
mod stream;
