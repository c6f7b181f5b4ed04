//! RAPID's speed argument: a predefined or declared `speeddata`, a literal, the switches `\V:=`
//! and `\T:=` ([`crate::program::speed`]).

use crate::program::speed::{duration, literal, path, Speed};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// RAPID's predefined `speeddata` (their `v_tcp`, mm/s, is the number in the name).
const RAPID_PREDEFINED: [u32; 25] = [
    5, 10, 20, 30, 40, 50, 60, 80, 100, 150, 200, 300, 400, 500, 600, 800, 1000, 1500, 2000, 2500,
    3000, 4000, 5000, 6000, 7000,
];

/// A RAPID module's `speeddata` by lower-case name: its `v_tcp` (mm/s) and declaration's line,
/// or why it has none in the file.
pub(crate) type RapidSpeeds = HashMap<String, std::result::Result<(f64, u64), String>>;

/// The speed of the RAPID motion `first` (`movel`, `movec`: a path speed; `movej`, `moveabsj`) whose speed argument
/// is `argument` (`v100`, `vcut\V:=120`, `v100\T:=2`), with the module's `declared` speeds.
///
/// # Errors
/// A literal speed or time outside its limits, naming the line.
pub(crate) fn speed(
    line: u64,
    first: &str,
    argument: Option<&str>,
    declared: &RapidSpeeds,
) -> Result<Speed> {
    if !matches!(first, "movel" | "movec") {
        return Ok(Speed::Joint);
    }
    let Some(argument) = argument else {
        return Ok(Speed::Unread("no speed argument".into()));
    };
    let name = argument.split('\\').next().unwrap_or("").trim();
    let switch = |key: &str| {
        (argument.split('\\').skip(1)).find_map(|s| {
            let (k, v) = s.split_once(":=")?;
            k.trim().eq_ignore_ascii_case(key).then(|| v.trim())
        })
    };
    let unread = |v: &str| {
        Speed::Unread(format!(
            "{}: a variable or expression, which stiffid does not evaluate",
            short(v)
        ))
    };
    if let Some(t) = switch("T") {
        let what = format!("\\T:={t}");
        return literal(t).map_or(Ok(unread(&what)), |s| duration(line, &what, s));
    }
    if let Some(v) = switch("V") {
        let what = format!("\\V:={v}");
        return literal(v).map_or(Ok(unread(&what)), |mm_s| path(line, &what, mm_s));
    }
    if name.starts_with('[') {
        let v_tcp =
            crate::program::cartesian::literal::parse(name, 0).and_then(|(n, _)| n.numbers(4));
        return match v_tcp {
            Some(v) => path(line, &format!("speeddata {name}"), v[0].0),
            None => Ok(unread(name)),
        };
    }
    let key = name.to_ascii_lowercase();
    if let Some(d) = declared.get(&key) {
        return match d {
            Ok((mm_s, from)) => path(line, &format!("speeddata {name} (line {from})"), *mm_s),
            Err(why) => Ok(Speed::Unread(why.clone())),
        };
    }
    let predefined = (key.strip_prefix('v'))
        .and_then(|n| n.parse::<u32>().ok())
        .filter(|n| RAPID_PREDEFINED.contains(n));
    match (predefined, key.as_str()) {
        (Some(mm_s), _) => path(line, name, f64::from(mm_s)),
        (None, "vmax") => Ok(Speed::Unread(
            "vmax: the robot's largest TCP speed, which the module does not state".into(),
        )),
        _ => Ok(Speed::Unread(format!(
            "{}: not a speeddata declared in this module nor a predefined one (v5 to v7000)",
            short(name)
        ))),
    }
}

/// Whether `v` mm/s is one of RAPID's predefined `speeddata` (`v100`).
pub(super) fn is_predefined(v: u32) -> bool {
    RAPID_PREDEFINED.contains(&v)
}
