//! The passes over buffers the simulator owns: the light pass (whole or in
//! bands on every core), the camera pass, and a render of both for one
//! shadow algorithm.

pub mod camera;
pub mod light;
pub mod render;
