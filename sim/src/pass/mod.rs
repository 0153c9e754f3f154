//! The passes over buffers the simulator owns: the light pass (whole or in
//! bands on every core), the camera pass, and the silhouette and stencil
//! passes over a scene's occluders; which units each algorithm uses; a
//! directional light's cascades.

pub mod algorithm;
pub mod camera;
pub mod cascade;
pub mod light;
pub(crate) mod occluders;

use umbra_core::{ConfigError, SubmitError};

/// Why a pass could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PassError {
    /// The configuration or a buffer is unusable.
    #[error("pass configuration: {0}")]
    Config(#[from] ConfigError),
    /// A draw call is malformed.
    #[error("draw call {draw}: {source}")]
    Submit {
        /// Which draw call.
        draw: usize,
        /// What is wrong with it.
        source: SubmitError,
    },
    /// A banded light pass was given a probe that counts events: a banded
    /// pass reports none (count them with a serial pass).
    #[error("a banded light pass reports no events: count them with a serial pass")]
    BandsWatched,
}
