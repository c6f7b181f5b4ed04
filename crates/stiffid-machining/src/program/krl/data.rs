//! A generated `.src` split as KUKA System Software stores a module: each motion's point
//! declared in the `.dat` beside it (`DECL E6POS XP1={..}`, `DECL E6AXIS XP1={..}`, between
//! `DEFDAT NAME` and `ENDDAT`) and the motion naming it (`LIN XP1 C_DIS`, `CIRC XP2, XP3`),
//! as the KSS 8 operating and programming instructions show a module's two files.

use std::fmt::Write;

/// The `.src` text `src` of the program `name` (one `super::generate` wrote: every motion
/// `PTP`, `LIN` or `CIRC` to literal aggregates) with its points named `XP1`, `XP2`, .. in
/// order, and its `.dat`: the points declared (`E6POS` for a Cartesian aggregate, `E6AXIS`
/// for axis angles), their values as written.
#[must_use]
pub(crate) fn split(name: &str, src: &str) -> (String, String) {
    let mut out = String::with_capacity(src.len());
    let mut decls = String::new();
    let mut n = 0usize;
    for line in src.split_inclusive('\n') {
        let keyword = ["PTP ", "LIN ", "CIRC "]
            .into_iter()
            .find(|k| line.starts_with(k) && line[k.len()..].starts_with('{'));
        let Some(keyword) = keyword else {
            out += line;
            continue;
        };
        out += keyword;
        let mut rest = &line[keyword.len()..];
        let mut first = true;
        while let Some(end) = rest.starts_with('{').then(|| closing(rest)).flatten() {
            n += 1;
            let aggregate = &rest[1..end];
            let (kind, members) = match aggregate.strip_prefix("E6POS:") {
                Some(m) => ("E6POS", m.trim_start()),
                None => ("E6AXIS", aggregate),
            };
            let _ = writeln!(decls, "DECL {kind} XP{n}={{{members}}}");
            if !first {
                out += ", ";
            }
            let _ = write!(out, "XP{n}");
            first = false;
            rest = &rest[end + 1..];
            rest = rest.strip_prefix(',').unwrap_or(rest);
        }
        out += rest;
    }
    let data = format!("&ACCESS RVP\n&REL 1\nDEFDAT {name}\n{decls}ENDDAT\n");
    (out, data)
}

/// The index in `s` (which starts with `{`) of the `}` closing it.
fn closing(s: &str) -> Option<usize> {
    let mut depth = 0usize;
    for (i, c) in s.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return Some(i);
                }
            }
            _ => {}
        }
    }
    None
}
