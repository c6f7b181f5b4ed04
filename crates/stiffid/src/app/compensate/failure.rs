//! A failure of the streamed job: the library's error, placed in the input it came from, or the
//! front end's sink's own.

use stiffid_core::Error;

/// A failure of the streamed path: the library's, or the sink's.
pub(super) enum Failure<E> {
    Library(Error),
    Sink(E),
}

impl<E> From<Error> for Failure<E> {
    fn from(e: Error) -> Self {
        Failure::Library(e)
    }
}

impl<E: From<Error>> Failure<E> {
    pub(super) fn into_error(self, name: &str) -> E {
        match self {
            Failure::Library(e) => in_input(name, e).into(),
            Failure::Sink(e) => e,
        }
    }
}

/// `error` placed in the input `name`; an option's error (the free tool axis' grid, the program's
/// name) as it is.
pub(super) fn in_input(name: &str, error: Error) -> Error {
    match error {
        e @ Error::InvalidOption { .. } => e,
        e => Error::Input {
            source_name: name.to_string(),
            error: Box::new(e),
        },
    }
}
