//! The shadow unit: filters, tests, bias and lookup culling against direct evaluation.

mod settle;
pub(crate) mod shadow_unit;
