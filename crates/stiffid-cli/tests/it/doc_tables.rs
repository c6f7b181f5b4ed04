//! The user documentation's tables stay readable: no cell longer than [`MAX_CELL`] characters
//! (what a row cannot say in that goes into the prose under its table, linked from the row), and
//! every row with as many cells as its table's header (a `|` inside a code span must be written
//! `\|`, or it splits the cell). The maintainers' `docs/ARCHITECTURE.md` is not checked.

use std::path::{Path, PathBuf};

/// The longest table cell the user documentation holds, in characters.
const MAX_CELL: usize = 400;

fn repo() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// The user documentation: the README, the reference, the guide, the model and every language page.
fn user_docs() -> Vec<PathBuf> {
    let mut docs: Vec<PathBuf> = [
        "README.md",
        "docs/reference.md",
        "docs/guide.md",
        "docs/model.md",
    ]
    .iter()
    .map(|p| repo().join(p))
    .collect();
    let mut pages: Vec<PathBuf> = std::fs::read_dir(repo().join("docs/programs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    pages.sort();
    docs.extend(pages);
    docs
}

/// The cells of a table row, split at each `|` that is not escaped.
fn cells(row: &str) -> Vec<&str> {
    let row = row.trim();
    let mut out = Vec::new();
    let (mut start, mut escaped) = (0, false);
    for (i, c) in row.char_indices() {
        match c {
            '\\' => escaped = !escaped,
            '|' if !escaped => {
                out.push(&row[start..i]);
                start = i + 1;
            }
            _ => escaped = false,
        }
    }
    out.push(&row[start..]);
    // The text before the first `|` and after the last one is no cell.
    out[1..out.len() - 1].iter().map(|c| c.trim()).collect()
}

/// Every problem of the tables of `text`: a cell too long, a row with another count of cells than
/// its header; each as `line: what`.
fn table_problems(text: &str) -> Vec<String> {
    let (mut fenced, mut header) = (false, None::<usize>);
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced || !line.starts_with('|') {
            header = None;
            continue;
        }
        let row = cells(line);
        let count = *header.get_or_insert(row.len());
        if row.len() != count {
            out.push(format!(
                "line {}: {} cells, the header {count} (write a `|` in a cell as `\\|`)",
                n + 1,
                row.len()
            ));
        }
        for cell in row.iter().filter(|c| c.chars().count() > MAX_CELL) {
            let start: String = cell.chars().take(60).collect();
            out.push(format!(
                "line {}: a cell of {} characters (at most {MAX_CELL}: move the detail under the table): {start}...",
                n + 1,
                cell.chars().count()
            ));
        }
    }
    out
}

#[test]
fn the_user_docs_tables_have_short_cells_and_whole_rows() {
    let mut problems = Vec::new();
    for path in user_docs() {
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path
            .strip_prefix(repo())
            .unwrap_or(&path)
            .display()
            .to_string();
        problems.extend(
            table_problems(&text)
                .into_iter()
                .map(|p| format!("{name} {p}")),
        );
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_long_cell_and_a_split_row_are_found() {
    let long = "x".repeat(MAX_CELL + 1);
    let text = format!(
        "| a | b |\n|---|---|\n| `x \\| y` | {long} |\n| `p | q` | r |\n\n```\n| {long} |\n```\n"
    );
    let problems = table_problems(&text);
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(problems[0].starts_with("line 3: a cell of 401 characters"));
    assert!(problems[1].starts_with("line 4: 3 cells, the header 2"));
    assert_eq!(cells("| a \\| b | c |"), vec!["a \\| b", "c"]);
}
