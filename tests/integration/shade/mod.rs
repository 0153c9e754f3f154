//! The camera pass's shading unit against an f64 evaluation of the same pixels.

mod camera_pass;
mod stream;
