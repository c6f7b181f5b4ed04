//! The names of generated programs: the main program's (its file's stem) and its
//! sub-programs' (`NAME_01`, ...), each an identifier of the language, not a reserved word and
//! within the controller's longest name; and the split into sub-programs (at most
//! [`super::Settings::moves_per_file`] moves each, and for FANUC LS at most 9999
//! numbered lines per file). [`check_plan`] checks them all from counts alone, before anything is
//! computed.

use super::{Dialect, Settings, MOVES_PER_FILE};
use crate::program::Generator;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};

/// The most sub-programs a program is split into.
pub(crate) const MAX_FILES: usize = 9999;

/// The most numbered lines of an LS program's `/MN` section: the pendant numbers them with four
/// digits (FANUC's line numbers run 1 to 9999).
pub(crate) const LS_MAX_LINES: usize = 9999;

/// The longest program name of a dialect's controller and language: KRL 24 (KUKA System
/// Software 8), RAPID 32 (RAPID identifiers), FANUC LS 36 (R-30iB Plus; R-30iA takes 8, the
/// default, [`default_name_length`]). [`Settings::name_length`] may lower it, never raise it.
pub(crate) fn max_name_length(dialect: Dialect) -> usize {
    dialect.controller().max_name_length()
}

/// The longest program name written by default: KRL 24, RAPID 32, LS 8 (R-30iA; later
/// controllers take longer names: raise [`Settings::name_length`] up to [`max_name_length`]).
pub(crate) fn default_name_length(dialect: Dialect) -> usize {
    dialect.controller().default_name_length()
}

/// The most moves one file of `dialect` holds with `settings`: [`Settings::moves_per_file`],
/// and for LS what fits its 9999 numbered lines with the main program's header.
pub fn moves_per_file(dialect: Dialect, settings: &Settings) -> usize {
    let most = (dialect.controller().generator()).and_then(|g| g.lines_per_file());
    most.map_or(settings.moves_per_file, |n| settings.moves_per_file.min(n))
}

/// Checks, before any computation, that a program `name` of `targets` targets can be written in
/// `dialect` with `settings`: the settings within their limits ([`Settings::validate`], the name
/// length within [`max_name_length`]), at most 9999 sub-programs (for LS, few enough for the main
/// program's calls to fit its 9999 lines) and every name the controller takes ([`check_name`]).
/// Returns the names: the main program's, then its sub-programs'.
///
/// # Errors
/// [`Error::InvalidOption`] naming the option: [`JobOption::NameLength`] above the
/// controller's, [`JobOption::MovesPerFile`] for too many sub-programs,
/// [`JobOption::ProgramName`] for a name the controller does not take; those of
/// [`Settings::validate`].
pub(crate) fn check_plan(
    dialect: Dialect,
    name: &str,
    settings: &Settings,
    targets: usize,
) -> Result<Vec<String>> {
    settings.validate()?;
    let generator = generator(dialect)?;
    let most = max_name_length(dialect);
    if let Some(n) = settings.name_length.filter(|&n| n > most) {
        return Err(Error::InvalidOption {
            option: JobOption::NameLength,
            message: format!(
                "{n}: {} takes names of at most {most} characters",
                dialect_name(dialect)
            ),
        });
    }
    let files = targets.div_ceil(moves_per_file(dialect, settings)).max(1);
    let max_files = (generator.lines_per_file()).map_or(MAX_FILES, |n| MAX_FILES.min(n));
    if files > max_files {
        return Err(Error::InvalidOption {
            option: JobOption::MovesPerFile,
            message: format!(
                "{} moves per file make {files} sub-programs; at most {max_files}: raise moves_per_file",
                settings.moves_per_file
            ),
        });
    }
    names(dialect, name, settings, files)
}

/// The main program's name and, for `files > 1`, the sub-programs' `NAME_01`, ...
fn names(dialect: Dialect, name: &str, settings: &Settings, files: usize) -> Result<Vec<String>> {
    let longest = settings.name_length.unwrap_or(default_name_length(dialect));
    check_name(dialect, name, longest)?;
    let mut names = vec![name.to_string()];
    if files > 1 {
        let width = files.to_string().len().max(2);
        for i in 1..=files {
            let sub = format!("{name}_{i:0width$}");
            // A sub-program's routine may take a prefix (RAPID: its module's name after an `r`).
            let prefix = (dialect.controller().generator()).map_or(0, |g| g.routine_prefix().len());
            if sub.len() + prefix > longest {
                return Err(Error::InvalidOption { option: JobOption::ProgramName, message: format!("{name:?}: the sub-programs' names ({sub} for {files} sub-programs) would be longer than {longest} characters, the controller's longest name (a setting: name_length): name the program shorter or raise moves_per_file") });
            }
            names.push(sub);
        }
    }
    Ok(names)
}

/// Refuses a program name the controller does not take (module docs).
pub fn check_name(dialect: Dialect, name: &str, longest: usize) -> Result<()> {
    let symbols = dialect.controller().name_symbols();
    let identifier = name.starts_with(|c: char| c.is_ascii_alphabetic())
        && (name.chars()).all(|c| c.is_ascii_alphanumeric() || c == '_' || symbols.contains(c));
    let reserved = reserved_words(dialect)
        .iter()
        .any(|w| w.eq_ignore_ascii_case(name));
    let message = if !identifier {
        format!("expected letters, digits and _{}, starting with a letter (the program is named after its file: rename the file)", symbols.chars().map(|c| format!(" or {c}")).collect::<String>())
    } else if name.len() > longest {
        format!(
            "{} characters: the controller takes at most {longest} (a setting: name_length)",
            name.len()
        )
    } else if reserved {
        format!(
            "a reserved word of {} (rename the file)",
            dialect_name(dialect)
        )
    } else if is_device_name(name) {
        "a device name of Windows, which no controller's or PC's file takes (rename the file)"
            .to_string()
    } else {
        return Ok(());
    };
    Err(Error::InvalidOption {
        option: JobOption::ProgramName,
        message: format!("{name:?}: {message}"),
    })
}

/// `CON`, `PRN`, `AUX`, `NUL`, `COM0`..`COM9`, `LPT0`..`LPT9` in any case: names Windows keeps
/// for devices, whatever the extension (the controllers' and their PCs' file systems).
fn is_device_name(name: &str) -> bool {
    let upper = name.to_ascii_uppercase();
    let numbered = |prefix: &str| {
        upper
            .strip_prefix(prefix)
            .is_some_and(|d| d.len() == 1 && d.as_bytes()[0].is_ascii_digit())
    };
    matches!(upper.as_str(), "CON" | "PRN" | "AUX" | "NUL") || numbered("COM") || numbered("LPT")
}

fn dialect_name(d: Dialect) -> &'static str {
    d.controller().title()
}

/// What writes new programs of `dialect`.
///
/// # Errors
/// [`Error::InvalidField`] (`out`) for a language whose programs are read and written back,
/// never generated (none today).
pub(crate) fn generator(dialect: Dialect) -> Result<&'static dyn Generator> {
    dialect.controller().generator().ok_or_else(|| Error::InvalidField {
        field: "out".into(),
        message: format!("a G-code path is written as a new robot program in {}; {} programs are read and written back compensated, not generated", generated(), dialect.controller().key().to_ascii_uppercase()),
    })
}

/// The languages programs are generated in, for messages: `KRL, RAPID or LS`.
fn generated() -> String {
    let keys: Vec<String> = (Dialect::ALL.iter())
        .filter(|d| d.controller().generator().is_some())
        .map(|d| d.controller().key().to_ascii_uppercase())
        .collect();
    crate::text::or_list(&keys)
}

/// The words a program may not be named (module docs; docs/reference.md cites the lists), and
/// the names of the data stiffid declares in it.
fn reserved_words(dialect: Dialect) -> &'static [&'static str] {
    dialect.controller().reserved_words()
}

/// `settings` with room in each file for the process lines `inserted` where the language limits
/// a file's lines ([`Generator::lines_per_file`]): fewer moves per file.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::MovesPerFile`]) when they leave room for fewer than
/// the least moves per file.
pub(super) fn room_for(
    generator: &dyn Generator,
    settings: &Settings,
    inserted: &[String],
) -> Result<Settings> {
    let extra: usize = inserted.iter().map(|s| s.lines().count()).sum();
    let Some(limit) = generator.lines_per_file().filter(|_| extra > 0) else {
        return Ok(*settings);
    };
    let room = limit.saturating_sub(extra);
    if room < *MOVES_PER_FILE.start() {
        return Err(Error::InvalidOption {
            option: JobOption::MovesPerFile,
            message: format!("{extra} process instructions leave room for {room} moves in a file of at most {limit} lines"),
        });
    }
    Ok(Settings {
        moves_per_file: settings.moves_per_file.min(room),
        ..*settings
    })
}
