//! A robot program written back under another file name: the name it declares follows the file's,
//! as the controller calls a program by its file's name (KUKA System Software refuses a `.src`
//! whose `DEF` is not its file's name; loading an LS file replaces the program its `/PROG` line
//! names, whatever the file is called, as loading a `.jbi` does the job its `//NAME` names). A RAPID module's name is not its file's: it is kept.

use super::Dialect;

/// `text`, a program of `dialect`, with the name it declares replaced by `name`: KRL's first
/// `DEF NAME(` (also `GLOBAL DEF`), LS's `/PROG  NAME`, INFORM's `//NAME NAME`; every other byte as it was. A RAPID
/// program, or one that declares no name, comes back unchanged.
///
/// # Examples
/// ```
/// use stiffid_machining::program::{rename::renamed, Dialect};
/// let krl = "&ACCESS RVP\nDEF pocket( )\n  PTP {A1 0}\nEND\n";
/// assert_eq!(renamed(krl, Dialect::Krl, "pocket_c"), "&ACCESS RVP\nDEF pocket_c( )\n  PTP {A1 0}\nEND\n");
/// let ls = "/PROG  POCKET\n/ATTR\n";
/// assert_eq!(renamed(ls, Dialect::FanucLs, "POCKET_C"), "/PROG  POCKET_C\n/ATTR\n");
/// ```
pub fn renamed(text: &str, dialect: Dialect, name: &str) -> String {
    let controller = dialect.controller();
    let span = declared(
        text,
        |line| controller.declares_name(line),
        controller.name_symbols(),
    );
    match span {
        Some((start, end)) => format!("{}{name}{}", &text[..start], &text[end..]),
        None => text.to_string(),
    }
}

/// A KRL `.dat`, `text`, with the name its `DEFDAT` declares replaced by `name` (KUKA System
/// Software pairs a `.src` and its `.dat` by the module name both declare); every other byte as
/// it was.
///
/// # Examples
/// ```
/// use stiffid_machining::program::rename::renamed_data;
/// let dat = "&ACCESS RVP\nDEFDAT  pocket PUBLIC\nENDDAT\n";
/// assert_eq!(renamed_data(dat, "pocket_c"), "&ACCESS RVP\nDEFDAT  pocket_c PUBLIC\nENDDAT\n");
/// ```
pub fn renamed_data(text: &str, name: &str) -> String {
    let keyword = |line: &str| {
        let upper = line.to_ascii_uppercase();
        upper
            .strip_prefix("DEFDAT")
            .filter(|r| r.starts_with(char::is_whitespace))
            .map(|r| line.len() - r.len())
    };
    match declared(text, keyword, "") {
        Some((start, end)) => format!("{}{name}{}", &text[..start], &text[end..]),
        None => text.to_string(),
    }
}

/// The byte span in `text` of the name on the first line where `keyword` finds the end of the
/// declaring keyword (an offset in the line with its leading blanks, and a byte order mark,
/// removed): the identifier after the blanks that follow it (with the language's `symbols`:
/// INFORM's `-`).
fn declared(
    text: &str,
    keyword: impl Fn(&str) -> Option<usize>,
    symbols: &str,
) -> Option<(usize, usize)> {
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim_start_matches('\u{feff}').trim_start();
        let indent = line.len() - trimmed.len();
        if let Some(after) = keyword(trimmed) {
            let rest = &trimmed[after..];
            let blanks = rest.len() - rest.trim_start().len();
            let start = offset + indent + after + blanks;
            let length = rest
                .trim_start()
                .find(|c: char| {
                    !(c.is_ascii_alphanumeric() || c == '_' || c == '$' || symbols.contains(c))
                })
                .unwrap_or(rest.trim_start().len());
            return (length > 0).then_some((start, start + length));
        }
        offset += line.len();
    }
    None
}
