//! What a pass costs: architecture files ([`arch`]), the work the timing
//! model charges ([`work`]), the timing model itself ([`timing`]), a
//! pass's time and its ledgers ([`ledger`], [`dram`]), the reports it
//! gives ([`report`]), the silicon of its units ([`silicon`]), the map
//! cache, the map's storage schemes.

pub mod arch;
pub mod cache;
pub mod dram;
pub mod ledger;
pub mod report;
pub mod silicon;
pub mod stack;
pub mod storage;
pub mod timing;
pub mod work;
