//! A typed choice in a file as its one spelling: serialized through its
//! `Display`, read back through its `FromStr` (for `#[serde(with = …)]`).
//! Rows and records hold the typed value; the text is only what a file
//! shows.

use std::fmt::Display;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serializer};

/// Serialize `value` as its `Display`.
///
/// # Errors
/// The serializer's.
pub(crate) fn serialize<T: Display, S: Serializer>(value: &T, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(value)
}

/// Read a value back through its `FromStr`, its error in the message.
///
/// # Errors
/// The text does not parse.
pub(crate) fn deserialize<'de, T, D>(d: D) -> Result<T, D::Error>
where
    T: FromStr,
    T::Err: Display,
    D: Deserializer<'de>,
{
    let text = String::deserialize(d)?;
    text.parse().map_err(|e| serde::de::Error::custom(format!("`{text}`: {e}")))
}
