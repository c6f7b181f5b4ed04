//! RAPID's `Offs` and `RelTool` of a point with constant arguments (ABB, *Technical reference
//! manual - RAPID Instructions, Functions and Data types*, the functions `Offs` and `RelTool`):
//!
//! - `Offs(p, x, y, z)`: `p` displaced by `(x, y, z)` mm along the axes of its work object
//!   (the target's frame), its orientation kept;
//! - `RelTool(p, x, y, z \Rx:=a \Ry:=b \Rz:=c)`: `p` displaced by `(x, y, z)` mm along the tool's
//!   axes at `p`, then turned `a` deg about the tool's x axis, `b` about the new y axis, `c` about
//!   the new z axis (the manual's order).
//!
//! `p` is a `robtarget` literal, one declared in the module, or itself an `Offs` or `RelTool`
//! of one; every other argument a number written in the call (a variable or an expression is
//! the controller's to compute: refused naming the line). The target is where the function
//! lands; compensated, the point `p` is written so that the same function lands on the
//! compensated pose ([`crate::program::cartesian::Cartesian::pose`]): a point `p` that other
//! motions also visit takes one value only, so writing refuses a program whose visits' points
//! would differ, naming their lines.

use crate::program::at;
use crate::program::cartesian::Cartesian;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use std::ops::Range;
use stiffid_core::common::limits::{self, ANGLE_DEG, LENGTH_MM};
use stiffid_core::Result;

/// The function.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Function {
    /// `Offs`: a displacement in the work object's axes.
    Offs,
    /// `RelTool`: a displacement and rotation in the tool's axes.
    RelTool,
}

/// The constant arguments after the point: the displacement (mm) and, for `RelTool`, the
/// rotations about x, y, z (deg, 0 where not given).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Arguments {
    xyz_mm: [f64; 3],
    rxyz_deg: [f64; 3],
}

impl Function {
    /// The function an identifier names (case-insensitive), if one of these.
    pub(super) fn of(ident: &str) -> Option<Self> {
        match ident.to_ascii_lowercase().as_str() {
            "offs" => Some(Function::Offs),
            "reltool" => Some(Function::RelTool),
            _ => None,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Function::Offs => "Offs",
            Function::RelTool => "RelTool",
        }
    }

    /// Adds the displacement of `args` to the target `c` (module docs).
    pub(super) fn apply(self, c: &mut Cartesian, args: &Arguments) {
        let d = Translation3::from(Vector3::from(args.xyz_mm) * 1e-3);
        match self {
            Function::Offs => c.before = Isometry3::from(d) * c.before,
            Function::RelTool => {
                let [a, b, g] = args.rxyz_deg.map(f64::to_radians);
                let r = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), a)
                    * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), b)
                    * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), g);
                c.after = c.after * d * r;
            }
        }
    }
}

/// The point's bytes in `code` and the constant arguments of the call of `f` whose `(` is at
/// byte `open` of `code`, the motion's argument ending at byte `end`.
///
/// # Errors
/// Naming `line`: no closing parenthesis, another count of arguments than 4, an argument that
/// is not a number written in the call, a switch other than `RelTool`'s `\Rx`, `\Ry`, `\Rz`, a
/// value outside its limits ([`LENGTH_MM`], [`ANGLE_DEG`]).
pub(super) fn arguments(
    line: u64,
    f: Function,
    code: &str,
    (open, end): (usize, usize),
    nums: &super::num::Nums,
) -> Result<(Range<usize>, Arguments)> {
    let name = f.name();
    let bad = |what: String| at(line, format!("{name}: {what}"));
    let close =
        closing(&code[..end], open).ok_or_else(|| bad("expected its closing ')'".into()))?;
    let inner = &code[open + 1..close];
    let parts = super::arguments::top_level(inner);
    let [point, x, y, z] = parts.as_slice() else {
        return Err(bad(format!(
            "expected 4 arguments (a point, x, y, z), found {}",
            parts.len()
        )));
    };
    let (z, switches) = inner[z.clone()]
        .split_once('\\')
        .unwrap_or((&inner[z.clone()], ""));
    let mut args = Arguments {
        xyz_mm: [0.0; 3],
        rxyz_deg: [0.0; 3],
    };
    let texts = [&inner[x.clone()], &inner[y.clone()], z];
    for (k, text) in texts.into_iter().enumerate() {
        let axis = ["x", "y", "z"][k];
        args.xyz_mm[k] = number(text, nums).map_err(|why| bad(not_constant(axis, text, &why)))?;
    }
    limits::check(&format!("{name} x, y, z"), &args.xyz_mm, &LENGTH_MM)
        .map_err(|e| bad(e.to_string()))?;
    for s in switches.split('\\').filter(|s| !s.trim().is_empty()) {
        let (key, value) = s.split_once(":=").unwrap_or((s, ""));
        let k = match (f, key.trim().to_ascii_lowercase().as_str()) {
            (Function::RelTool, "rx") => 0,
            (Function::RelTool, "ry") => 1,
            (Function::RelTool, "rz") => 2,
            _ => {
                return Err(bad(format!(
                    "\\{}: not a switch of {name} stiffid reads (RelTool's \\Rx, \\Ry, \\Rz)",
                    key.trim()
                )))
            }
        };
        let what = format!("\\{}", key.trim());
        args.rxyz_deg[k] =
            number(value, nums).map_err(|why| bad(not_constant(&what, value, &why)))?;
    }
    limits::check(
        &format!("{name} \\Rx, \\Ry, \\Rz"),
        &args.rxyz_deg,
        &ANGLE_DEG,
    )
    .map_err(|e| bad(e.to_string()))?;
    let after = code[close + 1..end].trim_start();
    if !(after.is_empty() || after.starts_with('\\')) {
        return Err(bad("the point is an expression around the function; stiffid reads Offs and RelTool of a point as the whole target".into()));
    }
    let from = open + 1;
    Ok((from + point.start..from + point.end, args))
}

/// Why an argument is refused.
fn not_constant(what: &str, text: &str, why: &str) -> String {
    format!(
        "{what} = '{}' is not a number written in the call nor arithmetic of num data the module states ({why}): its value is the controller's",
        text.trim()
    )
}

/// The value of an argument: a number written as is, or arithmetic of the module's `num` data
/// ([`super::num`]); why not.
fn number(text: &str, nums: &super::num::Nums) -> std::result::Result<f64, String> {
    match constant(text) {
        Some(v) => Ok(v),
        None => super::num::value(text, &|n| nums.get(n).cloned()),
    }
}

/// A number written as is (`-12.5`, `1E2`), `None` for anything else.
fn constant(text: &str) -> Option<f64> {
    let t = text.trim();
    let numeric = t.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '-' | '+' | '.'));
    t.parse::<f64>().ok().filter(|v| numeric && v.is_finite())
}

/// The byte of the `)` that closes the `(` at byte `open` of `code`, outside strings.
fn closing(code: &str, open: usize) -> Option<usize> {
    let (mut depth, mut in_string) = (0i32, false);
    for (i, c) in code[open..].char_indices() {
        match c {
            '"' => in_string = !in_string,
            '(' | '[' if !in_string => depth += 1,
            ')' | ']' if !in_string => {
                depth -= 1;
                if depth == 0 {
                    return (c == ')').then_some(open + i);
                }
            }
            ';' if !in_string => return None,
            _ => {}
        }
    }
    None
}
