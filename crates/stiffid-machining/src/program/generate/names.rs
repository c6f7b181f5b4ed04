//! The names of generated programs: the main program's (its file's stem) and its
//! sub-programs' (`NAME_01`, ...), each an identifier of the language, not a reserved word and
//! within the controller's longest name; and the split into sub-programs (at most
//! [`super::Settings::moves_per_file`] moves each, and for FANUC LS at most [`LS_MAX_LINES`]
//! numbered lines per file). [`check_plan`] checks them all from counts alone, before anything is
//! computed.

use super::{Dialect, Settings};
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};

/// The most sub-programs a program is split into.
pub const MAX_FILES: usize = 9999;

/// The most numbered lines of an LS program's `/MN` section: the pendant numbers them with four
/// digits (FANUC's line numbers run 1 to 9999).
pub const LS_MAX_LINES: usize = 9999;

/// The lines an LS main program's header adds before its moves or calls (`! set UTOOL`, six
/// remarks of the tool frame's values, `UFRAME_NUM`, `UTOOL_NUM`).
pub(super) const LS_HEADER_LINES: usize = 9;

/// The longest program name of a dialect's controller and language: KRL 24 (KUKA System
/// Software 8), RAPID 32 (RAPID identifiers), FANUC LS 36 (R-30iB Plus; R-30iA takes 8, the
/// default, [`default_name_length`]). [`Settings::name_length`] may lower it, never raise it.
pub fn max_name_length(dialect: Dialect) -> usize {
    match dialect {
        Dialect::Krl => 24,
        Dialect::Rapid => 32,
        Dialect::FanucLs => 36,
        Dialect::Inform => 32,
    }
}

/// The longest program name written by default: KRL 24, RAPID 32, LS 8 (R-30iA; later
/// controllers take longer names: raise [`Settings::name_length`] up to [`max_name_length`]).
pub fn default_name_length(dialect: Dialect) -> usize {
    match dialect {
        Dialect::FanucLs => 8,
        d => max_name_length(d),
    }
}

/// The most moves one file of `dialect` holds with `settings`: [`Settings::moves_per_file`],
/// and for LS what fits [`LS_MAX_LINES`] numbered lines with the main program's header.
pub fn moves_per_file(dialect: Dialect, settings: &Settings) -> usize {
    match dialect {
        Dialect::FanucLs => settings.moves_per_file.min(LS_MAX_LINES - LS_HEADER_LINES),
        _ => settings.moves_per_file,
    }
}

/// Checks, before any computation, that a program `name` of `targets` targets can be written in
/// `dialect` with `settings`: the settings within their limits ([`Settings::validate`], the name
/// length within [`max_name_length`]), at most [`MAX_FILES`] sub-programs (for LS, few enough for
/// the main program's calls to fit [`LS_MAX_LINES`]) and every name the controller takes
/// ([`check_name`]). Returns the names: the main program's, then its sub-programs'.
///
/// # Errors
/// [`Error::InvalidOption`] naming the option: [`JobOption::NameLength`] above the
/// controller's, [`JobOption::MovesPerFile`] for too many sub-programs,
/// [`JobOption::ProgramName`] for a name the controller does not take; those of
/// [`Settings::validate`].
pub fn check_plan(
    dialect: Dialect,
    name: &str,
    settings: &Settings,
    targets: usize,
) -> Result<Vec<String>> {
    settings.validate()?;
    if dialect == Dialect::Inform {
        return Err(Error::InvalidField {
            field: "out".into(),
            message: "a G-code path is written as a new robot program in KRL, RAPID or LS; INFORM jobs are read and written back compensated, not generated".into(),
        });
    }
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
    let max_files = match dialect {
        Dialect::FanucLs => MAX_FILES.min(LS_MAX_LINES - LS_HEADER_LINES),
        _ => MAX_FILES,
    };
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
            // A RAPID sub-program's routine is its module's name after an `r`.
            if sub.len() + usize::from(dialect == Dialect::Rapid) > longest {
                return Err(Error::InvalidOption { option: JobOption::ProgramName, message: format!("{name:?}: the sub-programs' names ({sub} for {files} sub-programs) would be longer than {longest} characters, the controller's longest name (a setting: name_length): name the program shorter or raise moves_per_file") });
            }
            names.push(sub);
        }
    }
    Ok(names)
}

/// Refuses a program name the controller does not take (module docs).
pub fn check_name(dialect: Dialect, name: &str, longest: usize) -> Result<()> {
    let identifier = name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    let reserved = reserved_words(dialect)
        .iter()
        .any(|w| w.eq_ignore_ascii_case(name));
    let message = if !identifier {
        "expected letters, digits and _, starting with a letter (the program is named after its file: rename the file)".to_string()
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
    match d {
        Dialect::Krl => "KUKA KRL",
        Dialect::Rapid => "ABB RAPID",
        Dialect::FanucLs => "FANUC LS",
        Dialect::Inform => "Yaskawa INFORM",
    }
}

/// The words a program may not be named (module docs; docs/reference.md cites the lists), and
/// the names of the data stiffid declares in it.
fn reserved_words(dialect: Dialect) -> &'static [&'static str] {
    match dialect {
        Dialect::Krl => &[
            "AND",
            "ANIN",
            "ANOUT",
            "AXIS",
            "B_AND",
            "B_EXOR",
            "B_NOT",
            "B_OR",
            "BAS",
            "BOOL",
            "BRAKE",
            "C_DIS",
            "C_ORI",
            "C_PTP",
            "C_SPL",
            "C_VEL",
            "CASE",
            "CAST_FROM",
            "CAST_TO",
            "CHAR",
            "CIRC",
            "CIRC_REL",
            "CONST",
            "CONTINUE",
            "DECL",
            "DEF",
            "DEFAULT",
            "DEFDAT",
            "DEFFCT",
            "DELAY",
            "DO",
            "E6AXIS",
            "E6POS",
            "ELSE",
            "END",
            "ENDDAT",
            "ENDFCT",
            "ENDFOR",
            "ENDIF",
            "ENDLOOP",
            "ENDSPLINE",
            "ENDSWITCH",
            "ENDWHILE",
            "ENUM",
            "EXIT",
            "EXOR",
            "EXT",
            "EXTFCT",
            "FALSE",
            "FOR",
            "FRAME",
            "GLOBAL",
            "GOTO",
            "HALT",
            "IF",
            "IMPORT",
            "INTERRUPT",
            "INT",
            "IS",
            "LIN",
            "LIN_REL",
            "LOOP",
            "MAXIMUM",
            "MINIMUM",
            "NOT",
            "OR",
            "POS",
            "PRIO",
            "PTP",
            "PTP_REL",
            "PUBLIC",
            "REAL",
            "REPEAT",
            "RESUME",
            "RETURN",
            "SCIRC",
            "SEC",
            "SIGNAL",
            "SLIN",
            "SPL",
            "SPLINE",
            "SPTP",
            "STEP",
            "STRUC",
            "SWITCH",
            "THEN",
            "TO",
            "TRIGGER",
            "TRUE",
            "UNTIL",
            "WAIT",
            "WHEN",
            "WHILE",
        ],
        Dialect::Rapid => &[
            "ALIAS",
            "AND",
            "BACKWARD",
            "CASE",
            "CONNECT",
            "CONST",
            "DEFAULT",
            "DIV",
            "DO",
            "ELSE",
            "ELSEIF",
            "ENDFOR",
            "ENDFUNC",
            "ENDIF",
            "ENDMODULE",
            "ENDPROC",
            "ENDRECORD",
            "ENDTEST",
            "ENDTRAP",
            "ENDWHILE",
            "ERROR",
            "EXIT",
            "FALSE",
            "FOR",
            "FROM",
            "FUNC",
            "GOTO",
            "IF",
            "INOUT",
            "LOCAL",
            "MOD",
            "MODULE",
            "NOSTEPIN",
            "NOT",
            "NOVIEW",
            "OR",
            "PERS",
            "PROC",
            "RAISE",
            "READONLY",
            "RECORD",
            "RETRY",
            "RETURN",
            "STEP",
            "SYSMODULE",
            "TEST",
            "THEN",
            "TO",
            "TRAP",
            "TRUE",
            "TRYNEXT",
            "UNDO",
            "VAR",
            "VIEWONLY",
            "WHILE",
            "WITH",
            "XOR",
            "main",
            "tspindle",
            "wpart",
            "vrapid",
            "zpath",
        ],
        Dialect::FanucLs => &[
            "ABORT", "AND", "CALL", "CNT", "CONFIG", "ELSE", "END", "ENDFOR", "ENDIF", "FINE",
            "FOR", "IF", "JMP", "LBL", "MOD", "NOT", "OFF", "ON", "OR", "PAUSE", "RUN", "SELECT",
            "THEN", "TO", "WAIT",
        ],
        Dialect::Inform => &[],
    }
}
