//! The date a generated program states (LS `CREATE` and `MODIFIED`, INFORM `///DATE`): a
//! program is reproducible, the same input giving the same bytes, so the date is not the clock's
//! but the one the settings give ([`super::Settings::date_s`]): the front ends set it from
//! `SOURCE_DATE_EPOCH` (seconds since 1970-01-01 00:00 UTC, the reproducible-builds
//! convention) when the environment sets it, else 1970-01-01 00:00 UTC.

use stiffid_core::{Error, Result};

/// The environment variable of the date ([module docs](self)).
pub const VARIABLE: &str = "SOURCE_DATE_EPOCH";
/// The latest date taken, seconds since 1970 (9999-12-31 23:59:59 UTC).
pub(crate) const MAX_EPOCH_S: i64 = 253_402_300_799;

/// A date and time, UTC.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stamp {
    /// The year, 1970 to 9999.
    pub year: i64,
    /// The month, 1 to 12.
    pub month: u32,
    /// The day, 1 to 31.
    pub day: u32,
    /// The hour, minute and second.
    pub time: (u32, u32, u32),
}

impl Stamp {
    /// The date `seconds` after 1970-01-01 00:00 UTC (0 to 253 402 300 799).
    pub fn at(seconds: i64) -> Self {
        let (days, s) = (seconds.div_euclid(86_400), seconds.rem_euclid(86_400));
        // Howard Hinnant's days-to-civil algorithm.
        let z = days + 719_468;
        let era = z.div_euclid(146_097);
        let doe = z - era * 146_097;
        let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
        let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
        let mp = (5 * doy + 2) / 153;
        let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
        let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
        let year = yoe + era * 400 + i64::from(month <= 2);
        let time = ((s / 3600) as u32, (s % 3600 / 60) as u32, (s % 60) as u32);
        Self {
            year,
            month,
            day,
            time,
        }
    }
}

/// The date of generated programs given as `SOURCE_DATE_EPOCH`'s text (`text`: whole seconds
/// since 1970-01-01 00:00 UTC), for [`super::Settings::date_s`]. A front end reads the
/// environment and calls this; the library reads no environment.
///
/// # Errors
/// [`Error::InvalidField`] (`SOURCE_DATE_EPOCH`) for a value that is not a whole number of
/// seconds from 0 to 253 402 300 799 (9999-12-31 23:59:59 UTC).
pub fn epoch(text: &str) -> Result<i64> {
    match text.trim().parse::<i64>() {
        Ok(s) if (0..=MAX_EPOCH_S).contains(&s) => Ok(s),
        _ => Err(Error::InvalidField {
            field: VARIABLE.into(),
            message: format!("{text:?}: expected the date of generated programs as whole seconds since 1970-01-01 00:00 UTC, 0 to {MAX_EPOCH_S} (the reproducible-builds convention); unset it for 1970-01-01"),
        }),
    }
}
