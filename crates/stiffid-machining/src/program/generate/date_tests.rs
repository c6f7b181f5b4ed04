//! The generated programs' dates (`crate::program::generate::date`): the calendar's.

use crate::program::generate::date::Stamp;

#[test]
fn a_date_is_the_calendars() {
    // Python's datetime.fromtimestamp(s, UTC) of each.
    for (s, want) in [
        (0, (1970, 1, 1, (0, 0, 0))),
        (951_782_400, (2000, 2, 29, (0, 0, 0))),
        (1_764_203_461, (2025, 11, 27, (0, 31, 1))),
        (4_107_542_400, (2100, 3, 1, (0, 0, 0))),
        (253_402_300_799, (9999, 12, 31, (23, 59, 59))),
    ] {
        let d = Stamp::at(s);
        assert_eq!((d.year, d.month, d.day, d.time), want, "{s}");
    }
}
