//! The checks of a URDF's text before the XML reader reads it: what the reader would misname
//! or pass over without a word (an empty file, a DTD, nesting too deep, an element after the
//! root, a misspelt element).

use crate::common::limits;

/// Fails for what the XML reader would misname: an empty file, and a document type definition
/// (`<!DOCTYPE`, `<!ENTITY`), which the reader does not expand.
pub(super) fn check_text(text: &str) -> std::result::Result<(), String> {
    if text.trim().is_empty() {
        return Err("the file is empty: expected a URDF document (<robot name=\"...\">)".into());
    }
    if text.contains("<!DOCTYPE") || text.contains("<!ENTITY") {
        return Err("DTDs are not supported (<!DOCTYPE> or <!ENTITY>): expand the entities first (for example `xmllint --noent robot.urdf`)".into());
    }
    Ok(())
}

/// Fails if the element nesting of `text` is deeper than [`limits::MAX_XML_DEPTH`], if an
/// element follows the document's root element (the XML reader stops at the root's end and
/// drops it), or if a joint, or a link's inertial, visual or collision, holds a misspelt element
/// ([`misspelt`]: `<orgin>`, which the XML reader would pass over). Comments, CDATA, declarations and quoted
/// attribute values are skipped, so nothing hides an element.
pub(super) fn check_elements(text: &str) -> std::result::Result<(), String> {
    let b = text.as_bytes();
    let (mut i, mut depth, mut roots) = (0, 0usize, 0usize);
    let mut open: Vec<&str> = Vec::new();
    let skip_to = |from: usize, end: &str| {
        text[from..]
            .find(end)
            .map_or(b.len(), |k| from + k + end.len())
    };
    while let Some(k) = text[i..].find('<') {
        i += k;
        let rest = &text[i..];
        if rest.starts_with("<!--") {
            i = skip_to(i, "-->");
        } else if rest.starts_with("<![CDATA[") {
            i = skip_to(i, "]]>");
        } else if rest.starts_with("<?") || rest.starts_with("<!") {
            i = skip_to(i, ">");
        } else if rest.starts_with("</") {
            depth = depth.saturating_sub(1);
            open.pop();
            i = skip_to(i, ">");
        } else {
            let (end, self_closing) = tag_end(b, i + 1);
            roots += usize::from(depth == 0);
            if roots > 1 {
                return Err(second_root(&text[i..end]));
            }
            let name = element_name(&text[i + 1..end]);
            if let Some(meant) = misspelt(&open, name) {
                let line = text[..i].matches('\n').count() + 1;
                let parent = open.last().copied().unwrap_or_default();
                return Err(format!(
                    "line {line}: <{}> in a <{parent}> is not a URDF element; did you mean <{meant}>? (URDF readers pass over an element they do not know, leaving its value at the default)",
                    limits::short(name)
                ));
            }
            if !self_closing {
                open.push(name);
                depth += 1;
                if depth > limits::MAX_XML_DEPTH {
                    return Err(format!(
                        "elements nest deeper than {} levels (a URDF nests about 5)",
                        limits::MAX_XML_DEPTH
                    ));
                }
            }
            i = end;
        }
    }
    Ok(())
}

/// The name of the element whose tag, after its `<`, is `tag`.
fn element_name(tag: &str) -> &str {
    let end = tag
        .find(|c: char| c.is_whitespace() || c == '/' || c == '>')
        .unwrap_or(tag.len());
    &tag[..end]
}

/// The element of the URDF format that `name`, opened inside the elements `open` (outermost
/// first), is probably a misspelling of: one defined in a joint or in a link's inertial, visual
/// or collision (ROS wiki, urdf/XML/joint and urdf/XML/link) within two edits of `name` and not
/// `name`. URDF readers pass over an element they do not know (legacy and extension elements,
/// `<joint_properties>`, `<drake:gear_ratio>`, pass here too), so a misspelt `<orgin>` would
/// leave the joint's frame at zero without a word.
fn misspelt<'a>(open: &[&str], name: &str) -> Option<&'a str> {
    let defined: &[&'a str] = match open {
        [.., "robot", "joint"] => &[
            "origin",
            "parent",
            "child",
            "axis",
            "calibration",
            "dynamics",
            "limit",
            "mimic",
            "safety_controller",
        ],
        [.., "robot", "link", "inertial"] => &["origin", "mass", "inertia"],
        [.., "robot", "link", "visual"] => &["origin", "geometry", "material"],
        [.., "robot", "link", "collision"] => &["origin", "geometry"],
        _ => return None,
    };
    if defined.contains(&name) {
        return None;
    }
    (defined.iter())
        .map(|d| (crate::io::edit_distance(name, d), *d))
        .filter(|(distance, _)| *distance <= 2)
        .min()
        .map(|(_, d)| d)
}

/// The error of an element `tag` after the document's root element.
fn second_root(tag: &str) -> String {
    format!(
        "an element follows the document's root element: '{}' (a URDF holds one <robot>)",
        limits::short(tag)
    )
}

/// The index after the `>` ending the tag that starts before `from`, and whether it is `/>`;
/// `>` inside quoted attribute values does not count.
fn tag_end(b: &[u8], from: usize) -> (usize, bool) {
    let mut quote = None;
    for (k, &c) in b.iter().enumerate().skip(from) {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, b'"' | b'\'') => quote = Some(c),
            (None, b'>') => return (k + 1, k > from && b[k - 1] == b'/'),
            _ => {}
        }
    }
    (b.len(), false)
}
