//! RAPID's aggregate literals (`[[x,y,z],[q1,q2,q3,q4]]`, `[TRUE,[..],".."]`) as a tree, every
//! number with its bytes in the text.

use super::super::number_at;
use std::ops::Range;

/// One member of a literal.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Node {
    /// `[..]`.
    List(Vec<Node>),
    /// A number and its span.
    Number(f64, Range<usize>),
    /// A word (`TRUE`, `FALSE`, an identifier), upper case.
    Word(String),
    /// A string's content.
    Text(String),
}

impl Node {
    /// The members of a list, `None` for anything else.
    pub(crate) fn list(&self) -> Option<&[Node]> {
        match self {
            Node::List(items) => Some(items),
            _ => None,
        }
    }

    /// The `n` numbers of a list of numbers, with their spans.
    pub(crate) fn numbers(&self, n: usize) -> Option<Vec<(f64, Range<usize>)>> {
        let items = self.list().filter(|i| i.len() == n)?;
        items
            .iter()
            .map(|i| match i {
                Node::Number(v, s) => Some((*v, s.clone())),
                _ => None,
            })
            .collect()
    }

    /// Whether a word is `TRUE` (`Some(true)`), `FALSE`, or neither (`None`).
    pub(crate) fn boolean(&self) -> Option<bool> {
        match self {
            Node::Word(w) if w == "TRUE" => Some(true),
            Node::Word(w) if w == "FALSE" => Some(false),
            _ => None,
        }
    }
}

/// The deepest nesting of brackets a literal may have: RAPID's data types nest three deep
/// (`tooldata`'s `tload`), and a deeper literal is no literal of theirs (nor, read
/// recursively, one to exhaust the stack on).
pub(crate) const MAX_DEPTH: usize = 8;

/// The literal opening with `[` at or after blanks from byte `from` of `code`, and the byte
/// after its closing `]`; `None` when there is no well-formed literal there, or one nested
/// deeper than [`MAX_DEPTH`].
pub(crate) fn parse(code: &str, from: usize) -> Option<(Node, usize)> {
    parse_within(code, from, MAX_DEPTH)
}

/// [`parse`] with `depth` more levels of brackets allowed.
fn parse_within(code: &str, from: usize, depth: usize) -> Option<(Node, usize)> {
    let bytes = code.as_bytes();
    let skip = |mut i: usize| {
        while i < bytes.len() && bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        i
    };
    let at = skip(from);
    match *bytes.get(at)? {
        b'[' => {
            let depth = depth.checked_sub(1)?;
            let mut items = Vec::new();
            let mut i = skip(at + 1);
            if bytes.get(i) == Some(&b']') {
                return Some((Node::List(items), i + 1));
            }
            loop {
                let (item, next) = parse_within(code, i, depth)?;
                items.push(item);
                let next = skip(next);
                match *bytes.get(next)? {
                    b',' => i = next + 1,
                    b']' => return Some((Node::List(items), next + 1)),
                    _ => return None,
                }
            }
        }
        b'"' => {
            let end = code[at + 1..].find('"')? + at + 1;
            Some((Node::Text(code[at + 1..end].to_string()), end + 1))
        }
        c if c.is_ascii_alphabetic() || c == b'_' => {
            let end = code[at..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .map_or(code.len(), |e| at + e);
            Some((Node::Word(code[at..end].to_ascii_uppercase()), end))
        }
        _ => {
            let (v, span) = number_at(code, at)?;
            let end = span.end;
            Some((Node::Number(v, span), end))
        }
    }
}
