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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::urdf;
    use nalgebra::{Translation3, UnitQuaternion};

    /// Six joints in a row, one without `<origin>`, one in single quotes with an `<origin>`
    /// closed by `</origin>`, a commented-out copy of a chain joint, a fixed joint between two
    /// revolute ones, a mimic joint off the chain, a mesh and an inertial.
    const TEXT: &str = r#"<?xml version="1.0"?>
<robot name="six &amp; more">
  <link name="l0"><visual><geometry><mesh filename="package://p/meshes/l0.stl"/></geometry></visual></link>
  <link name="l1"><inertial><origin xyz="0 0 0.1"/><mass value="12"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="l1b"/><link name="l2"/><link name="l3"/><link name="l4"/><link name="l5"/><link name="l6"/><link name="cb"/>
  <!-- <joint name="j2" type="revolute"><origin xyz="9 9 9"/></joint> -->
  <joint name="j1" type="revolute"><parent link="l0"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="fix" type="fixed"><parent link="l1"/><child link="l1b"/><origin xyz="0 0 0.4" rpy="0 0 0"/></joint>
  <joint name='j2' type='revolute'><parent link='l1b'/><child link='l2'/>
    <origin xyz='0.1 0 0' rpy='0 0 0'></origin><axis xyz='0 1 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>
  <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/><origin xyz="0 0 1" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j4" type="revolute"><parent link="l3"/><child link="l4"/><origin xyz="0.8 0 0.1" rpy="0 0 0"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j5" type="revolute"><parent link="l4"/><child link="l5"/><origin xyz="0.2 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j6" type="revolute"><parent link="l5"/><child link="l6"/><origin xyz="0.1 0 0" rpy="0 0 0"/><axis xyz="1 0 0"/><limit lower="-6" upper="6" effort="1" velocity="1"/></joint>
  <joint name="cbj" type="revolute"><parent link="l1"/><child link="cb"/><origin xyz="-0.3 0 0.1"/><axis xyz="0 1 0"/><mimic joint="j2" multiplier="-0.25"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"#;

    #[test]
    fn only_the_chain_origins_and_the_name_change() {
        let robot = urdf::parse(TEXT, "six.urdf", Some("l6")).unwrap();
        let source = robot.urdf_source().unwrap();
        assert_eq!(
            source.joints,
            ["j1", "j2", "j3", "j4", "j5", "j6"].map(String::from)
        );
        let origins: [Isometry3<f64>; 6] = std::array::from_fn(|i| {
            let k = i as f64 + 1.0;
            Isometry3::from_parts(
                Translation3::new(0.1 * k, -0.01 * k, 0.001 * k),
                UnitQuaternion::from_euler_angles(0.01 * k, -0.02 * k, 0.03 * k),
            )
        });
        let text = with_origins(source, "six <calibrated>", &origins).unwrap();
        let back = urdf::parse(&text, "back.urdf", Some("l6")).unwrap();
        assert_eq!(back.name(), "six <calibrated>");
        for (got, want) in back.urdf_source().unwrap().origins.iter().zip(&origins) {
            let d = got.inverse() * want;
            assert!(d.translation.vector.norm() < 1e-15 && d.rotation.angle() < 1e-15);
        }
        for kept in [
            r#"<!-- <joint name="j2" type="revolute"><origin xyz="9 9 9"/></joint> -->"#,
            r#"<origin xyz="0 0 0.4" rpy="0 0 0"/>"#,
            r#"<origin xyz="-0.3 0 0.1"/><axis xyz="0 1 0"/><mimic joint="j2""#,
            r#"<mesh filename="package://p/meshes/l0.stl"/>"#,
            r#"<inertial><origin xyz="0 0 0.1"/><mass value="12"/>"#,
        ] {
            assert!(text.contains(kept), "{kept} lost:\n{text}");
        }
        assert!(!text.contains("</origin>") && !text.contains("0.1 0 0' rpy"));
        assert_eq!(back.masses(), robot.masses());
    }
}
