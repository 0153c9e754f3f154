//! The account of events: every unit reports the work it does.

mod accounting;
