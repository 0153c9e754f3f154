//! The depth block: the dual unit against the two smallest fragments, and depth quantization against the formats' formula.

mod dual_depth;
mod quantize;
