//! What every stage stands on: the library's errors and warnings, the documented limits of every
//! count and size a user gives, the user's choices as enums, progress reports and counted words.

pub mod choice;
pub mod error;
pub(crate) mod exact;
pub(crate) mod job_option;
#[cfg(feature = "schema")]
pub mod kind;
pub mod limits;
pub mod progress;
pub mod stop;
pub mod threads;
pub mod warning;
pub mod words;

#[cfg(test)]
mod stop_tests;
#[cfg(test)]
mod words_tests;
