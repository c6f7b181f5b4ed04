//! ABB RAPID (`.mod`): `MODULE NAME` with `PROC main()`, sub-programs `MODULE NAME_01` with
//! `PROC rNAME_01()` (module docs of [`crate::program::generate`]).

use crate::program::cartesian::flags::ConfigurationData;
use crate::program::generate::arcs::Form;
use crate::program::generate::date::Stamp;
use crate::program::generate::{in_work, number, v, Move, Part, Plan, Target, Targets};
use crate::program::{Arcs, ExternalGroup, Generator, Writing};
use std::fmt::Write;
use stiffid_core::Result;

/// The data the moves use, declared in the main module.
pub(crate) fn header(plan: &Plan, _main: &str, _subs: &[String]) -> String {
    let mut s = String::from(
        "  ! written by stiffid: compensated targets, the tool, work object and speeds below;\n  \
         ! check them for the cell before running\n",
    );
    // The real tool in joint-target programs too (`MoveAbsJ .., tspindle`).
    {
        let tool = &plan.tool.frame;
        let (mass, c) = plan.tool.payload.unwrap_or_default();
        let c = c * 1e3;
        let _ = writeln!(
            s,
            "  PERS tooldata tspindle := [TRUE,{},[{},[{},{},{}],[1,0,0,0],0,0,0]];",
            pose(tool),
            number(mass),
            number(c.x),
            number(c.y),
            number(c.z)
        );
        let _ = writeln!(
            s,
            "  PERS wobjdata wpart := [FALSE,TRUE,\"\",{},[[0,0,0],[1,0,0,0]]];",
            pose(&plan.world.inv_mul(&plan.work))
        );
    }
    let a = number(plan.approximation * 1e3);
    let _ = write!(
        s,
        "  CONST speeddata vrapid := [{},500,5000,1000];\n  \
         CONST zonedata zpath := [FALSE,{a},{a},{a},0.1,{a},0.1];\n",
        number(plan.settings.rapid_speed.min(plan.settings.max_tcp_speed) * 1e3)
    );
    s
}

/// `[q1,q2,q3,q4]` of a rotation, the scalar first and not negative.
fn quaternion(r: &nalgebra::UnitQuaternion<f64>) -> String {
    let q = r.quaternion();
    let sign = if q.w < 0.0 { -1.0 } else { 1.0 };
    format!(
        "[{},{},{},{}]",
        v(sign * q.w),
        v(sign * q.i),
        v(sign * q.j),
        v(sign * q.k)
    )
}

/// The moves of one file.
pub(crate) fn body(plan: &Plan, part: &Part) -> String {
    let mut s = String::with_capacity(part.targets.len() * 160);
    let n = part.targets.len();
    // The circle point of the `MoveC` the next target ends.
    let mut via: Option<String> = None;
    for (k, (t, m)) in part.targets.iter().zip(part.moves).enumerate() {
        let exact = part.last && k + 1 == n;
        s += part.before(k);
        let (speed, zone) = match m.feed() {
            None => ("vrapid".to_string(), "fine"),
            Some(f) => (
                format!("[{},500,5000,1000]", number(f * 1e3)),
                if exact { "fine" } else { "zpath" },
            ),
        };
        let _ = match plan.settings.targets {
            Targets::Joint => {
                let axes: Vec<String> = t.q_deg.iter().map(|x| v(*x)).collect();
                writeln!(
                    s,
                    "    MoveAbsJ [[{}],{}], {speed}, {zone}, tspindle\\WObj:=wpart;",
                    axes.join(","),
                    extax(t)
                )
            }
            Targets::Cartesian => {
                let (p, r) = in_work(plan, t);
                let super::ConfData([c1, c4, c6, cx]) = ConfigurationData::of(&t.arm);
                let target = format!(
                    "[[{},{},{}],{},[{c1},{c4},{c6},{cx}],{}]",
                    v(p.x),
                    v(p.y),
                    v(p.z),
                    quaternion(&r),
                    extax(t)
                );
                let (motion, target) = match (m, via.take()) {
                    (Move::ArcVia(_), _) => {
                        via = Some(target);
                        continue;
                    }
                    (Move::ArcEnd(_), Some(via)) => ("MoveC", format!("{via}, {target}")),
                    (Move::Rapid, _) => ("MoveJ", target),
                    _ => ("MoveL", target),
                };
                writeln!(
                    s,
                    "    {motion} {target}, {speed}, {zone}, tspindle\\WObj:=wpart;"
                )
            }
        };
    }
    s + part.after()
}

/// A target's `extjoint` `[eax_a,..,eax_f]`: the cell's external axes in order (mm or deg),
/// `9E9` for the logical axes the cell does not have.
fn extax(t: &Target) -> String {
    let axes: Vec<String> = (0..EXTAX)
        .map(|k| t.external.get(k).map_or("9E9".into(), |x| v(*x)))
        .collect();
    format!("[{}]", axes.join(","))
}

/// The logical external axes of an `extjoint`, `eax_a` to `eax_f`.
const EXTAX: usize = 6;

/// A RAPID `pose`: `[[x,y,z],[q1,q2,q3,q4]]` (mm).
fn pose(f: &nalgebra::Isometry3<f64>) -> String {
    let p = f.translation.vector * 1e3;
    format!(
        "[[{},{},{}],{}]",
        number(p.x),
        number(p.y),
        number(p.z),
        quaternion(&f.rotation)
    )
}

/// The main program's calls of its sub-programs.
pub(crate) fn calls(subs: &[String]) -> String {
    subs.iter().map(|n| format!("    r{n};\n")).collect()
}

/// A whole module.
pub(crate) fn wrap(name: &str, header: &str, body: &str, main: bool) -> String {
    match main {
        true => format!(
            "MODULE {name}\n{header}  PROC main()\n    ConfJ \\On;\n    ConfL \\On;\n{body}  ENDPROC\nENDMODULE\n"
        ),
        false => format!("MODULE {name}\n  PROC r{name}()\n{body}  ENDPROC\nENDMODULE\n"),
    }
}

/// What a RAPID module holds and how it writes it: a sub-program's routine is its module's name
/// after an `r`; a `tooldata` states the tool's mass in every program (the controller refuses a
/// tool of no mass; joint targets move with it too); `MoveC` with Cartesian targets; up to six
/// external axes `eax_a` to `eax_f`, the carrier's then the positioner's, in its `extjoint`
/// (ABB RAPID Reference Manual).
static WRITING: Writing = Writing {
    lines_per_file: None,
    routine_prefix: "r",
    states_mass: true,
    cartesian: true,
    pulses: false,
    arcs: Some(Arcs {
        form: Form::ViaEnd,
        joint_targets: false,
    }),
    carrier: ExternalGroup {
        most: EXTAX,
        form: "eax_a to eax_f",
    },
    positioner: ExternalGroup {
        most: EXTAX,
        form: "eax_a to eax_f",
    },
    process: Some(&super::process::FORM),
};

impl Generator for super::Rapid {
    fn header(&self, plan: &Plan, main: &str, subs: &[String]) -> String {
        header(plan, main, subs)
    }
    fn body(&self, plan: &Plan, part: &Part, _warnings: &mut Vec<String>) -> Result<String> {
        Ok(body(plan, part))
    }
    fn calls(&self, subs: &[String]) -> String {
        calls(subs)
    }
    fn wrap(&self, name: &str, header: &str, body: &str, main: bool, _date: Stamp) -> String {
        wrap(name, header, body, main)
    }
    fn writing(&self) -> &'static Writing {
        &WRITING
    }
}
