//! Fixed-length arrays in input files, read strictly.

use serde::Deserialize;

/// `N` values, exactly: an array of any other length is an error naming
/// its line, never cut or padded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Exact<const N: usize, T = f64>(pub [T; N]);

impl<'de, const N: usize, T: Deserialize<'de>> Deserialize<'de> for Exact<N, T> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<T>::deserialize(d)?;
        let n = v.len();
        v.try_into().map(Self).map_err(|_| serde::de::Error::invalid_length(n, &format!("{N} values").as_str()))
    }
}
