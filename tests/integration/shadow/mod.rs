//! The shadow unit: filters, tests, bias and lookup culling against direct evaluation.

mod settle;
mod shadow_unit;
