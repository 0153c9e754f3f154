//! The exact reference and the papers' claims measured against it.

mod cause;
mod claims;
mod metrics;
mod receivers;
mod reference;
