//! Fixed-length arrays read exactly: serde reads `[f64; 3]` from a longer TOML or JSON array
//! and drops the rest silently; these readers (`#[serde(deserialize_with = ...)]`) refuse any
//! other length, naming the length found and the one expected.

use serde::de::{Deserialize, Deserializer, Error};

/// An array of exactly `N` values.
struct Exact<T, const N: usize>([T; N]);

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let values = Vec::<T>::deserialize(d)?;
        let len = values.len();
        <[T; N]>::try_from(values)
            .map(Exact)
            .map_err(|_| D::Error::invalid_length(len, &format!("an array of length {N}").as_str()))
    }
}

/// `[T; N]`, exactly `N` values.
pub(crate) fn array<'de, D, T, const N: usize>(d: D) -> Result<[T; N], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Exact::<T, N>::deserialize(d).map(|e| e.0)
}

/// `Option<[T; N]>`, exactly `N` values when given (use with `#[serde(default)]`).
pub(crate) fn option<'de, D, T, const N: usize>(d: D) -> Result<Option<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Option::<Exact<T, N>>::deserialize(d).map(|o| o.map(|e| e.0))
}

/// `Vec<[T; N]>`, each exactly `N` values.
pub(crate) fn arrays<'de, D, T, const N: usize>(d: D) -> Result<Vec<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Vec::<Exact<T, N>>::deserialize(d).map(|v| v.into_iter().map(|e| e.0).collect())
}

/// `Option<Vec<[T; N]>>`, each exactly `N` values (use with `#[serde(default)]`).
pub(crate) fn option_arrays<'de, D, T, const N: usize>(
    d: D,
) -> Result<Option<Vec<[T; N]>>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Option::<Vec<Exact<T, N>>>::deserialize(d)
        .map(|o| o.map(|v| v.into_iter().map(|e| e.0).collect()))
}

/// `[[T; C]; R]`, exactly `R` rows of exactly `C` values.
pub(crate) fn matrix<'de, D, T, const R: usize, const C: usize>(
    d: D,
) -> Result<[[T; C]; R], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    let rows = Exact::<Exact<T, C>, R>::deserialize(d)?;
    Ok(rows.0.map(|r| r.0))
}

/// `Option<[[T; C]; R]>`, exactly `R` rows of exactly `C` values when given (use with
/// `#[serde(default)]`).
pub(crate) fn option_matrix<'de, D, T, const R: usize, const C: usize>(
    d: D,
) -> Result<Option<[[T; C]; R]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    let rows = Option::<Exact<Exact<T, C>, R>>::deserialize(d)?;
    Ok(rows.map(|r| r.0.map(|r| r.0)))
}
