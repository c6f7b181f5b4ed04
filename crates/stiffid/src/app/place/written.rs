//! The setup file written back with the part placed: its own text, every byte but the
//! `[workpiece]` table's, which holds the new `base_from_part`.

use nalgebra::Isometry3;

/// `text` (a setup file's TOML) with the body of its `[workpiece]` table replaced by one
/// `base_from_part`, `pose` (mm and fixed-axis roll, pitch, yaw in deg, to 1 nm and 1e-8 deg);
/// the table's header line (and its comment) and the comment and blank lines just before the
/// next table stay. Without a `[workpiece]` table, the new one is appended.
pub fn with_workpiece(text: &str, pose: &Isometry3<f64>) -> String {
    // Rounded to the digits written, `+ 0.0` turning a negative zero into 0.
    let round = |v: f64, digits: f64| (v * digits).round() / digits + 0.0;
    let t = pose.translation.vector.map(|v| round(v * 1e3, 1e6));
    let [r, p, y] = stiffid_core::robot::file::rpy(&pose.rotation);
    let [r, p, y] = [r, p, y].map(|a| round(a.to_degrees(), 1e8));
    let body = format!(
        "base_from_part = {{ xyz_mm = [{:.6}, {:.6}, {:.6}], rpy_deg = [{:.8}, {:.8}, {:.8}] }}\n",
        t.x, t.y, t.z, r, p, y
    );
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let header = |l: &str| l.trim_start().starts_with('[');
    let is_workpiece = |l: &str| {
        let l = l.trim();
        l.strip_prefix("[workpiece]")
            .is_some_and(|rest| rest.trim().is_empty() || rest.trim_start().starts_with('#'))
    };
    let Some(start) = lines.iter().position(|l| is_workpiece(l)) else {
        let gap = if text.is_empty() || text.ends_with('\n') {
            ""
        } else {
            "\n"
        };
        return format!("{text}{gap}\n[workpiece]\n{body}");
    };
    let next = (start + 1..lines.len())
        .find(|&i| header(lines[i]))
        .unwrap_or(lines.len());
    let mut end = next;
    while end > start + 1 && {
        let l = lines[end - 1].trim();
        l.is_empty() || l.starts_with('#')
    } {
        end -= 1;
    }
    let mut out: String = lines[..=start].concat();
    out.push_str(&body);
    out.push_str(&lines[end..].concat());
    out
}
