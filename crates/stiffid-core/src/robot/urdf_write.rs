//! A URDF written back with corrected joint origins: the document a robot was read from
//! ([`super::urdf::UrdfSource`]) with the `<origin>` of each chain joint replaced, everything
//! else (links, meshes, inertials, mimic joints, fixed joints, comments) kept as it was.
//!
//! The text is edited, not regenerated: urdf-rs parses, it does not write, and a regenerated
//! document would lose what stiffid does not read. Comments and CDATA sections are skipped, so a
//! commented-out joint is never edited.

use super::urdf::UrdfSource;
use nalgebra::Isometry3;
use std::ops::Range;

/// `source`'s document with the robot named `name` and the origins of its six chain joints
/// replaced by `origins` (parent link to joint frame, m; base first).
///
/// # Errors
/// A message when a chain joint's element cannot be found in the text.
pub fn with_origins(
    source: &UrdfSource,
    name: &str,
    origins: &[Isometry3<f64>; 6],
) -> Result<String, String> {
    let text = &source.text;
    let skipped = skipped(text);
    let mut edits: Vec<(Range<usize>, String)> = Vec::new();
    if let Some(range) = attribute(text, &skipped, "robot", None, "name") {
        edits.push((range, xml_escaped(name)));
    }
    for (joint, origin) in source.joints.iter().zip(origins) {
        let element = element(text, &skipped, "joint", joint)
            .ok_or_else(|| format!("joint '{joint}' not found in the URDF text"))?;
        edits.push(origin_edit(text, &skipped, element, origin));
    }
    edits.sort_by_key(|(r, _)| r.start);
    let mut out = String::with_capacity(text.len() + 512);
    let mut at = 0;
    for (range, new) in edits {
        out.push_str(&text[at..range.start]);
        out.push_str(&new);
        at = range.end;
    }
    out.push_str(&text[at..]);
    Ok(out)
}

/// The edit giving the joint element at `element` (its opening tag's end, its closing tag's
/// start) the origin `origin`: its `<origin .../>` replaced, or one inserted after the opening tag.
fn origin_edit(
    text: &str,
    skipped: &[Range<usize>],
    (open_end, close_start): (usize, usize),
    origin: &Isometry3<f64>,
) -> (Range<usize>, String) {
    let xml = origin_xml(origin);
    let inner = open_end..close_start;
    match tags(text, skipped, "origin").find(|r| inner.contains(&r.start)) {
        Some(tag) => {
            let end = match text[tag.start..tag.end].ends_with("/>") {
                true => tag.end,
                false => text[tag.end..close_start]
                    .find("</origin>")
                    .map_or(tag.end, |k| tag.end + k + "</origin>".len()),
            };
            (tag.start..end, xml)
        }
        None => (open_end..open_end, format!("\n      {xml}")),
    }
}

/// An `<origin>` element of `t` (xyz in m, rpy the fixed-axis roll, pitch, yaw in rad).
pub fn origin_xml(t: &Isometry3<f64>) -> String {
    let p = t.translation.vector;
    let [r, pi, y] = super::file::rpy(&t.rotation);
    format!(
        "<origin xyz=\"{:?} {:?} {:?}\" rpy=\"{r:?} {pi:?} {y:?}\"/>",
        p.x, p.y, p.z
    )
}

/// The byte ranges of comments, CDATA sections and declarations of `text`.
fn skipped(text: &str) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(k) = text[i..].find("<!") {
        let start = i + k;
        let end_mark = match &text[start..] {
            r if r.starts_with("<!--") => "-->",
            r if r.starts_with("<![CDATA[") => "]]>",
            _ => ">",
        };
        let end = text[start..]
            .find(end_mark)
            .map_or(text.len(), |e| start + e + end_mark.len());
        out.push(start..end);
        i = end;
    }
    out
}

/// The opening tags `<name ...>` of `text` outside `skipped`, each as its byte range.
fn tags(text: &str, skipped: &[Range<usize>], name: &str) -> std::vec::IntoIter<Range<usize>> {
    let open = format!("<{name}");
    let tags: Vec<Range<usize>> = (text.match_indices(open.as_str()))
        .map(|(k, _)| k)
        .filter(|&k| {
            let next = text.as_bytes().get(k + open.len()).copied();
            matches!(next, Some(b' ' | b'\t' | b'\n' | b'\r' | b'>' | b'/'))
                && !skipped.iter().any(|r| r.contains(&k))
        })
        .map(|k| k..tag_end(text, k))
        .collect();
    tags.into_iter()
}

/// The index after the `>` ending the tag starting at `start`; `>` inside quoted attribute
/// values does not count.
fn tag_end(text: &str, start: usize) -> usize {
    let mut quote = None;
    for (k, c) in text.bytes().enumerate().skip(start + 1) {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, b'"' | b'\'') => quote = Some(c),
            (None, b'>') => return k + 1,
            _ => {}
        }
    }
    text.len()
}

/// The byte range of the value of attribute `attr` of the first `<tag>` (named `name` when
/// given) in `text`.
fn attribute(
    text: &str,
    skipped: &[Range<usize>],
    tag: &str,
    name: Option<&str>,
    attr: &str,
) -> Option<Range<usize>> {
    tags(text, skipped, tag)
        .filter_map(|t| value_of(text, t, attr))
        .find(|v| name.is_none_or(|n| unescaped(&text[v.clone()]) == n))
}

/// The byte range of attribute `attr`'s value inside the tag at `tag`.
fn value_of(text: &str, tag: Range<usize>, attr: &str) -> Option<Range<usize>> {
    let t = &text[tag.clone()];
    let mut from = 0;
    while let Some(k) = t[from..].find(attr) {
        let at = from + k;
        from = at + attr.len();
        // `at > 0`: the tag starts with `<`.
        if !t.as_bytes()[at - 1].is_ascii_whitespace() {
            continue;
        }
        let Some(value) = t[from..]
            .trim_start()
            .strip_prefix('=')
            .map(str::trim_start)
        else {
            continue;
        };
        let Some(q) = value.chars().next().filter(|c| matches!(c, '"' | '\'')) else {
            continue;
        };
        let start = t.len() - value.len() + 1;
        let end = start + t[start..].find(q)?;
        return Some(tag.start + start..tag.start + end);
    }
    None
}

/// The joint element named `name`: the end of its opening tag and the start of its closing tag.
fn element(text: &str, skipped: &[Range<usize>], tag: &str, name: &str) -> Option<(usize, usize)> {
    let open = tags(text, skipped, tag)
        .find(|t| value_of(text, t.clone(), "name").is_some_and(|v| unescaped(&text[v]) == name))?;
    let close = format!("</{tag}>");
    let end = open.end + text[open.end..].find(close.as_str())?;
    Some((open.end, end))
}

fn unescaped(s: &str) -> String {
    s.replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

fn xml_escaped(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
