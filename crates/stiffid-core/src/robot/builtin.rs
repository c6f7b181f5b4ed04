//! Named texts embedded in the library (robot presets, setups): one lookup for every table.

use crate::{Error, Result};

/// `(name, text)` entries, the texts embedded with `include_str!`.
pub(crate) type Table = [(&'static str, &'static str)];

/// The names of `table`, in its order.
pub(crate) fn names(table: &'static Table) -> impl Iterator<Item = &'static str> {
    table.iter().map(|(n, _)| *n)
}

/// The text named `name` in `table`.
///
/// # Errors
/// [`Error::Unknown`] of `kind` ("robot preset", "setup"), listing the names of `table`, if no
/// entry has this name.
pub(crate) fn text(table: &'static Table, kind: &'static str, name: &str) -> Result<&'static str> {
    table
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .ok_or_else(|| Error::Unknown {
            kind,
            name: name.to_string(),
            known: names(table).collect::<Vec<_>>().join(", "),
        })
}
