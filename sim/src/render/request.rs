//! A render asked for parameter by parameter ([`RenderRequest`]): what the
//! command line and Python's keywords build through the declarations in
//! [`PARAMS`](super::params::PARAMS), before a scene fills in the image size.

use super::RenderConfig;
use crate::pass::algorithm::{Algorithm, UnknownAlgorithm};

/// A render asked for, parameter by parameter, before its scene fills in
/// what it leaves open (the image size) and the algorithm takes its
/// parameter: what the command line and Python's keywords build.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderRequest {
    /// The configuration's fields but the algorithm and the image size.
    pub(super) config: RenderConfig,
    /// The algorithm's name and the parameters of those that take one.
    pub(super) algo: &'static str,
    pub(super) bias1: f64,
    pub(super) offset: f64,
    /// The image size, where given.
    pub(super) width: Option<u32>,
    pub(super) height: Option<u32>,
}

impl RenderRequest {
    /// The default render ([`RenderConfig::DEFAULT`]) at its scene's
    /// image size.
    pub const DEFAULT: Self = Self {
        config: RenderConfig::DEFAULT,
        algo: RenderConfig::DEFAULT.algorithm.name(),
        bias1: Algorithm::DEFAULT_BIAS1,
        offset: Algorithm::DEFAULT_OFFSET,
        width: None,
        height: None,
    };

    /// The request of a configuration: every parameter as `cfg` has it.
    #[must_use]
    pub(crate) fn of(cfg: &RenderConfig) -> Self {
        Self {
            config: *cfg,
            algo: cfg.algorithm.name(),
            bias1: cfg.algorithm.bias_hi().unwrap_or(Algorithm::DEFAULT_BIAS1),
            offset: cfg.algorithm.offset().unwrap_or(Algorithm::DEFAULT_OFFSET),
            width: Some(cfg.width),
            height: Some(cfg.height),
        }
    }

    /// The configuration asked for, with the image `[width, height]` (a
    /// scene's) where the request leaves it open. Every value
    /// was checked as it was set; the configuration's check against a
    /// scene and the limits is [`RenderConfig::check`].
    ///
    /// # Errors
    /// [`UnknownAlgorithm`] when the algorithm's name is unknown (never,
    /// for a request built by [`RenderRequest::set`]).
    pub fn config(&self, [width, height]: [u32; 2]) -> Result<RenderConfig, UnknownAlgorithm> {
        let algorithm = Algorithm::named(self.algo, self.bias1, self.offset)?;
        Ok(RenderConfig {
            algorithm,
            width: self.width.unwrap_or(width),
            height: self.height.unwrap_or(height),
            ..self.config
        })
    }
}
