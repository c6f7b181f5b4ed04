//! File formats read by stiffid, as `&str -> Result<_, Error>` functions (no file I/O here but the
//! opening of [`input`] files and the writing of [`output`]): the
//! caller reads the file and adds its name to errors. `text` turns the bytes a caller read into
//! the text of an input, within the input size limit (`limits::MAX_INPUT_BYTES`); [`Capped`]
//! holds a reader of an input read in pieces to the same limit.
//!
//! - [`external`]: the external axis columns (`e1_mm`, `e2_deg`) every data file shares.
//! - [`input`]: the files a front end reads: regular files only, never a wait on a FIFO.
//! - [`measurements`]: the measurement CSV of an identification or validation.
//! - [`output`]: the files a front end writes: where a write lands, whether it may, whole files.
//! - `stiffid_machining::path`: the path (pose list) CSV of compensation.
//! - [`postures`]: the postures CSV of a group of postures.
//! - `stiffid_machining::program`: the joint targets of robot programs (KUKA KRL, ABB RAPID, FANUC LS).
//! - [`readings`]: the registration readings CSV (axis angles and tracker readings).
//! - [`reference`](mod@crate::setup::reference): a robot or setup named by a file path or a built-in name.
//! - [`stiffness`]: the stiffness JSON (joint stiffness and the covariance of the compliance).

pub mod external;
pub mod input;
pub mod measurements;
pub mod output;
pub mod postures;
pub mod readings;
pub mod stiffness;
mod temporaries;

use crate::common::error::ColumnProblem;
use crate::common::limits::{short, MAX_INPUT_BYTES};
use crate::{Error, Result};
use std::io::Read;

/// The text of an input file from its bytes as read: the reader stops after
/// `MAX_INPUT_BYTES` + 1 bytes (`Read::take`), so more than the limit means the file is larger.
///
/// # Errors
/// [`Error::Parse`] naming `source_name`: larger than the input limit, or not UTF-8 text (with
/// the first invalid byte, its offset, line and column).
pub fn text(source_name: &str, bytes: Vec<u8>) -> Result<String> {
    let error = |message: String| Error::Parse {
        source_name: source_name.to_string(),
        message,
    };
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(error(too_large()));
    }
    String::from_utf8(bytes)
        .map_err(|e| error(not_utf8(e.as_bytes(), e.utf8_error().valid_up_to())))
}

/// The character encoding a program's files were read in ([`program_texts`]), which its
/// compensated copy is written in ([`Encoding::encode`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Encoding {
    /// UTF-8 (ASCII is UTF-8).
    #[default]
    Utf8,
    /// ISO 8859-1: each byte one character (U+0000 to U+00FF), as the controllers' files in
    /// ISO 8859-1 or Windows-1252 (European backups: KUKA, FANUC, ABB) are read byte for byte.
    Latin1,
}

impl Encoding {
    /// `utf-8` or `latin-1`.
    pub fn name(self) -> &'static str {
        match self {
            Encoding::Utf8 => "utf-8",
            Encoding::Latin1 => "latin-1",
        }
    }

    /// `text` as the bytes of a file in this encoding: a file read in it is written back byte
    /// for byte where its text is unchanged (for [`Encoding::Latin1`], a byte order mark
    /// starting the text as UTF-8's, as [`program_texts`] read it).
    ///
    /// # Errors
    /// For [`Encoding::Latin1`], the first character beyond U+00FF, with its line.
    ///
    /// # Examples
    /// ```
    /// use stiffid_core::io::Encoding;
    /// assert_eq!(Encoding::Latin1.encode("; Z\u{fc}rich").unwrap(), b"; Z\xfcrich");
    /// assert_eq!(Encoding::Latin1.encode("\u{feff}; \u{fc}").unwrap(), b"\xef\xbb\xbf; \xfc");
    /// assert!(Encoding::Latin1.encode("a\n\u{20ac}").unwrap_err().contains("line 2"));
    /// ```
    pub fn encode(self, text: &str) -> std::result::Result<Vec<u8>, String> {
        if self == Encoding::Utf8 {
            return Ok(text.as_bytes().to_vec());
        }
        let (mark, text) = match text.strip_prefix(BOM) {
            Some(rest) => (BOM.as_bytes(), rest),
            None => (&[][..], text),
        };
        let mut line = 1;
        let bytes = (text.chars()).map(|c| {
            line += usize::from(c == '\n');
            u8::try_from(u32::from(c)).map_err(|_| {
                format!("'{c}' (U+{:04X}) on line {line} has no byte in Latin-1, the encoding the program was read in", u32::from(c))
            })
        });
        mark.iter().copied().map(Ok).chain(bytes).collect()
    }
}

/// The byte order mark: U+FEFF, in UTF-8 the bytes EF BB BF.
const BOM: &str = "\u{feff}";

/// `bytes` read as Latin-1, each byte one character, but a UTF-8 byte order mark at the start
/// (a file an editor saved beside a controller's, no Latin-1 text's first three characters),
/// read as the mark.
fn latin1(bytes: Vec<u8>) -> String {
    match bytes.strip_prefix(BOM.as_bytes()) {
        Some(rest) => BOM
            .chars()
            .chain(rest.iter().map(|b| char::from(*b)))
            .collect(),
        None => bytes.into_iter().map(char::from).collect(),
    }
}

/// The texts of a program's files (a KRL `.src` and its `.dat`) from their bytes as read, named
/// by `files`' names: UTF-8 when every file is; else each read as Latin-1 ([`Encoding::Latin1`],
/// byte for byte, a UTF-8 byte order mark at a file's start read as the mark), the encoding of
/// controllers' European backups. Either way a program is text: no file may hold a control
/// character other than a tab, a line or page break and DOS's end-of-file mark.
///
/// # Errors
/// [`Error::Parse`] naming the file: larger than the input limit, not text (a control byte,
/// named with its offset, line and column), or neither UTF-8 nor Latin-1.
///
/// # Examples
/// ```
/// use stiffid_core::io::{program_texts, Encoding};
/// let (texts, encoding) = program_texts(vec![("p.src", b"; Z\xfcrich\r\n".to_vec())]).unwrap();
/// assert_eq!((texts[0].as_str(), encoding), ("; Z\u{fc}rich\r\n", Encoding::Latin1));
/// assert!(program_texts(vec![("p.src", vec![0xfc, 0x00])]).is_err());
/// // A NUL in a UTF-8 file: no text either.
/// assert!(program_texts(vec![("p.nc", b"G1 X1\0\n".to_vec())]).is_err());
/// // A .src saved with a byte order mark beside a Latin-1 .dat: the mark read as one.
/// let files = vec![("p.src", b"\xef\xbb\xbfDEF p( )".to_vec()), ("p.dat", b"; \xe9".to_vec())];
/// let (texts, _) = program_texts(files).unwrap();
/// assert_eq!(texts[0], "\u{feff}DEF p( )");
/// ```
pub fn program_texts(files: Vec<(&str, Vec<u8>)>) -> Result<(Vec<String>, Encoding)> {
    let control = |b: &u8| *b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r' | 0x0c | 0x1a);
    for (name, bytes) in files
        .iter()
        .filter(|(_, b)| b.len() as u64 <= MAX_INPUT_BYTES)
    {
        if let Some(at) = bytes.iter().position(control) {
            return Err(Error::Parse {
                source_name: name.to_string(),
                message: not_text(bytes, at),
            });
        }
    }
    let utf8 = files.iter().all(|(_, b)| std::str::from_utf8(b).is_ok());
    let texts =
        files.into_iter().map(
            |(name, bytes)| match utf8 || bytes.len() as u64 > MAX_INPUT_BYTES {
                true => text(name, bytes),
                false => Ok(latin1(bytes)),
            },
        );
    let encoding = if utf8 {
        Encoding::Utf8
    } else {
        Encoding::Latin1
    };
    Ok((texts.collect::<Result<_>>()?, encoding))
}

/// The message for a program's `bytes` that are not text: the control byte at `at`, its
/// offset, line and column.
fn not_text(bytes: &[u8], at: usize) -> String {
    let (line, column) = line_column(bytes, at);
    format!("not text: a control byte 0x{:02X} at offset {at}, line {line}, column {column} (an encrypted module or a binary file?)", bytes[at])
}

/// The line and column (1-based) of byte `at` of `bytes`.
fn line_column(bytes: &[u8], at: usize) -> (usize, usize) {
    let before = &bytes[..at];
    let line = before.iter().filter(|b| **b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|b| *b == b'\n')
        .map_or(0, |n| n + 1);
    (line, at - line_start + 1)
}

/// The message for `bytes` that are not UTF-8 from byte `at` on: the byte, its offset, line and
/// column, and the likely cause when it is one of Latin-1's letters (a controller's backup,
/// written in ISO 8859-1 or Windows-1252).
fn not_utf8(bytes: &[u8], at: usize) -> String {
    let (line, column) = line_column(bytes, at);
    let byte = bytes[at];
    let latin = if byte >= 0xa0 {
        "; Latin-1 or Windows-1252 text, as some controllers write their files? convert it to UTF-8 (iconv -f windows-1252 -t utf-8)"
    } else {
        ""
    };
    format!("not UTF-8 text (invalid byte 0x{byte:02X} at offset {at}, line {line}, column {column}){latin}")
}

/// The text of an input read from `reader` (a file the caller opened): at most
/// `MAX_INPUT_BYTES` + 1 bytes are read, then `text`.
///
/// # Errors
/// [`Error::Parse`] naming `source_name`: a read error (`cannot read: ...`), and those of `text`.
///
/// # Examples
/// ```
/// let text = stiffid_core::io::read_text("group.csv", &b"q1_deg"[..]).unwrap();
/// assert_eq!(text, "q1_deg");
/// ```
pub fn read_text(source_name: &str, reader: impl Read) -> Result<String> {
    text(source_name, read_bytes(source_name, reader)?)
}

/// The bytes of an input read from `reader` (a file the caller opened): at most
/// `MAX_INPUT_BYTES` + 1, so that more than the limit tells the file is larger (`text`,
/// [`program_texts`] refuse it).
///
/// # Errors
/// [`Error::Parse`] naming `source_name`: a read error (`cannot read: ...`).
pub fn read_bytes(source_name: &str, reader: impl Read) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    reader
        .take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::Parse {
            source_name: source_name.to_string(),
            message: format!("cannot read: {e}"),
        })?;
    Ok(bytes)
}

/// "larger than the input limit of 256 MiB": the one wording of [`text`] and [`Capped`].
fn too_large() -> String {
    format!(
        "larger than the input limit of {} MiB",
        MAX_INPUT_BYTES >> 20
    )
}

/// A reader of an input (a file the caller opened) that fails with "larger than the input limit"
/// once more than `MAX_INPUT_BYTES` have been read from it: the limit of `text` for inputs
/// read in pieces (`identify::streamed`).
///
/// # Examples
/// ```
/// use std::io::Read;
/// let mut small = stiffid_core::io::Capped::new(&b"q1_deg"[..]);
/// let mut text = String::new();
/// small.read_to_string(&mut text).unwrap();
/// assert_eq!(text, "q1_deg");
/// ```
#[derive(Debug)]
pub struct Capped<R> {
    inner: R,
    read: u64,
}

impl<R> Capped<R> {
    /// `inner`, nothing read yet.
    pub fn new(inner: R) -> Self {
        Capped { inner, read: 0 }
    }

    /// The reader inside, without the limit.
    pub fn into_inner(self) -> R {
        self.inner
    }
}

impl<R: Read> Read for Capped<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.read += n as u64;
        if self.read > MAX_INPUT_BYTES {
            return Err(std::io::Error::other(too_large()));
        }
        Ok(n)
    }
}

/// The error for a column `name` missing from the header at `line`.
pub fn missing(line: u64, name: &str) -> Error {
    Error::Column {
        line,
        column: None,
        name: name.into(),
        problem: ColumnProblem::Missing {
            missing: name.into(),
        },
    }
}

/// The hint for a header read as one column holding `;`: a spreadsheet that writes `;` between
/// columns (as in locales whose decimal mark is a comma); empty otherwise.
fn separator_hint<S: AsRef<str>>(names: &[S]) -> &'static str {
    match names {
        [only] if only.as_ref().contains(';') => {
            " (this header separates its columns with ';', as spreadsheets in some locales save \
             CSV: save it with ',' as the field separator and '.' as the decimal mark)"
        }
        _ => "",
    }
}

/// Checks that every name of a header (at `line`) is one of `known`, and none comes twice.
///
/// # Errors
/// [`ColumnProblem::Unknown`] (with a suggestion and `expected()`) or
/// [`ColumnProblem::Duplicate`], naming the column.
pub fn known_names<'a, S, I>(
    names: &[S],
    line: u64,
    known: I,
    expected: fn() -> String,
) -> Result<()>
where
    S: AsRef<str>,
    I: Iterator<Item = &'a str> + Clone,
{
    for (i, name) in names.iter().map(AsRef::as_ref).enumerate() {
        let problem = if !known.clone().any(|k| k == name) {
            ColumnProblem::Unknown {
                given: short(name),
                suggestion: suggestion(name, known.clone()).map(str::to_string),
                expected: expected() + separator_hint(names),
            }
        } else if names[..i].iter().any(|n| n.as_ref() == name) {
            ColumnProblem::Duplicate { given: short(name) }
        } else {
            continue;
        };
        return Err(Error::Column {
            line,
            column: Some(i + 1),
            name: String::new(),
            problem,
        });
    }
    Ok(())
}

/// The `known` column a misspelled one probably meant: the same but for case or a missing unit
/// suffix (`q4` for `q4_deg`), or at most two edits away.
fn suggestion<'a, I>(name: &str, known: I) -> Option<&'a str>
where
    I: Iterator<Item = &'a str> + Clone,
{
    let lower = name.to_lowercase();
    let unit_missing = |k: &str| {
        k.strip_prefix(lower.as_str())
            .is_some_and(|r| r.starts_with('_'))
    };
    known.clone().find(|k| unit_missing(k)).or_else(|| {
        known
            .map(|k| (edit_distance(&lower, k), k))
            .filter(|(d, _)| *d <= 2)
            .min()
            .map(|(_, k)| k)
    })
}

/// The Levenshtein distance between `a` and `b` (insertions, deletions and substitutions of a
/// character).
pub(crate) fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (diagonal + usize::from(ca != *cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// The line (1-based) of the record that starts at or after a byte of `body` (its line ends
/// skipped), counted on from the previous byte asked for (bytes asked for never decrease). Not
/// `csv`'s own line count, which is one too low after a `\r\n` line end (the `\n` is counted when
/// the next record is read, after its position was taken).
pub struct LineCount<'a> {
    body: &'a [u8],
    byte: usize,
    line: u64,
    comments: bool,
}

impl<'a> LineCount<'a> {
    /// Lines of `body`, counted from its start (line 1).
    pub(crate) fn new(body: &'a [u8]) -> Self {
        Self {
            body,
            byte: 0,
            line: 1,
            comments: false,
        }
    }

    /// `LineCount::new` (lines counted from the start) for a reader that skips comment lines (`#` first), which it reports at
    /// the comment's start.
    pub fn with_comments(body: &'a [u8]) -> Self {
        Self {
            comments: true,
            ..Self::new(body)
        }
    }

    /// The line of the record at `byte`.
    pub fn at(&mut self, byte: u64) -> u64 {
        let mut end = usize::try_from(byte).map_or(self.body.len(), |b| b.min(self.body.len()));
        loop {
            while matches!(self.body.get(end), Some(b'\r' | b'\n')) {
                end += 1;
            }
            if !(self.comments && self.body.get(end) == Some(&b'#')) {
                break;
            }
            end = self.body[end..]
                .iter()
                .position(|b| *b == b'\n')
                .map_or(self.body.len(), |n| end + n);
        }
        let end = end.max(self.byte);
        self.line += self.body[self.byte..end]
            .iter()
            .filter(|b| **b == b'\n')
            .count() as u64;
        self.byte = end;
        self.line
    }
}

/// A `csv` reader's error without its own position (the caller names the line, counted by
/// [`LineCount`]): `invalid UTF-8 in field 3`, or the reader's message.
pub fn csv_message(e: &csv::Error) -> String {
    match e.kind() {
        csv::ErrorKind::Utf8 { err, .. } => format!("invalid UTF-8 in field {}", err.field() + 1),
        csv::ErrorKind::Io(io) => io.to_string(),
        _ => e.to_string(),
    }
}
