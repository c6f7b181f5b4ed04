//! KUKA KRL (`.src`): `DEF NAME( )` ... `END` (module docs of [`crate::program::generate`]).

use crate::program::cartesian::flags::ConfigurationData;
use crate::program::generate::arcs::Form;
use crate::program::generate::date::Stamp;
use crate::program::generate::{
    in_work, number, v, zyx_deg, Move, Part, Plan, Target, Targets, RAPID_PERCENT,
};
use crate::program::{Arcs, ExternalGroup, Generator, Writing};
use std::fmt::Write;
use stiffid_core::Result;

/// The motion set-up at the top of the main program.
pub(crate) fn header(plan: &Plan) -> String {
    let mut s = String::from(
        "; written by stiffid: compensated targets, the tool, base and speeds below;\n\
         ; check them for the cell before running\n\
         BAS(#INITMOV, 0)\n",
    );
    let _ = write!(
        s,
        "BAS(#VEL_PTP, {})\nBAS(#ACC_PTP, {RAPID_PERCENT})\n\
         $VEL.ORI1 = 200\n$VEL.ORI2 = 200\n$ACC.CP = 1\n$ACC.ORI1 = 100\n$ACC.ORI2 = 100\n\
         $APO.CDIS = {}\n",
        number(plan.settings.rapid_joint_pct),
        number(plan.approximation * 1e3)
    );
    // The real tool and load in joint-target programs too: speeds and dynamics are the tool's.
    {
        let tool = (plan.numbers.tool).map(|(n, _)| format!("TOOL_DATA[{n}]"));
        let _ = writeln!(s, "$TOOL = {}", tool.unwrap_or(frame(&plan.tool.frame)));
        if let Some((mass, c)) = plan.tool.payload {
            let c = c * 1e3;
            let _ = writeln!(
                s,
                "$LOAD = {{M {}, CM {{X {}, Y {}, Z {}, A 0, B 0, C 0}}, J {{X 0, Y 0, Z 0}}}}",
                number(mass),
                number(c.x),
                number(c.y),
                number(c.z)
            );
        }
        let base = (plan.numbers.base).map(|(n, _)| format!("BASE_DATA[{n}]"));
        let _ = writeln!(
            s,
            "$BASE = {}",
            base.unwrap_or(frame(&plan.world.inv_mul(&plan.work)))
        );
    }
    s
}

/// A KRL `FRAME` (mm, deg).
fn frame(f: &nalgebra::Isometry3<f64>) -> String {
    let p = f.translation.vector * 1e3;
    let [a, b, c] = zyx_deg(&f.rotation);
    format!(
        "{{X {}, Y {}, Z {}, A {}, B {}, C {}}}",
        number(p.x),
        number(p.y),
        number(p.z),
        number(a),
        number(b),
        number(c)
    )
}

/// The moves of one file.
pub(crate) fn body(plan: &Plan, part: &Part) -> String {
    let mut s = String::with_capacity(part.targets.len() * 140);
    let mut speed: Option<f64> = None;
    // The via point of the circular move the next target ends.
    let mut via: Option<String> = None;
    let n = part.targets.len();
    for (k, (t, m)) in part.targets.iter().zip(part.moves).enumerate() {
        let exact = part.last && k + 1 == n;
        s += part.before(k);
        if let Some(f) = m.feed()
            && speed != Some(f)
        {
            let _ = writeln!(s, "$VEL.CP = {}", number(f));
            speed = Some(f);
        }
        let approximate = |c: &str| match (exact, m.feed()) {
            (false, Some(_)) => format!(" {c}"),
            _ => String::new(),
        };
        match plan.settings.targets {
            Targets::Joint => {
                let axes: Vec<String> = (0..6)
                    .map(|k| format!("A{} {}", k + 1, v(t.q_deg[k])))
                    .collect();
                let _ = writeln!(
                    s,
                    "PTP {{{}{}}}{}",
                    axes.join(", "),
                    external(t),
                    approximate("C_PTP")
                );
            }
            Targets::Cartesian => {
                let (p, r) = in_work(plan, t);
                let [a, b, c] = zyx_deg(&r);
                let super::StatusTurn { status, turn } = ConfigurationData::of(&t.arm);
                let pos = format!(
                    "{{E6POS: X {}, Y {}, Z {}, A {}, B {}, C {}{}, S 'B{status:03b}', T 'B{turn:06b}'}}",
                    v(p.x),
                    v(p.y),
                    v(p.z),
                    v(a),
                    v(b),
                    v(c),
                    external(t),
                );
                let _ = match (m, via.take()) {
                    (Move::ArcVia(_), _) => {
                        via = Some(pos);
                        Ok(())
                    }
                    (Move::ArcEnd(_), Some(via)) => {
                        writeln!(s, "CIRC {via},{pos}{}", approximate("C_DIS"))
                    }
                    (Move::Rapid, _) => writeln!(s, "PTP {pos}"),
                    _ => writeln!(s, "LIN {pos}{}", approximate("C_DIS")),
                };
            }
        }
    }
    s + part.after()
}

/// A target's external axes as `E6AXIS`/`E6POS` members, `, E1 .., E2 ..` (mm or deg, the
/// `$EX_AX_NUM` numbering in the cell's order); empty on a fixed base.
fn external(t: &Target) -> String {
    (t.external.iter().enumerate())
        .map(|(k, x)| format!(", E{} {}", k + 1, v(*x)))
        .collect()
}

/// The main program's calls of its sub-programs.
pub(crate) fn calls(subs: &[String]) -> String {
    subs.iter().map(|n| format!("{n}( )\n")).collect()
}

/// A whole `.src` file: the [`KSS_HEADER`], `DEF NAME( )` ... `END`.
pub(crate) fn wrap(name: &str, header: &str, body: &str) -> String {
    format!("{KSS_HEADER}DEF {name}( )\n{header}{body}END\n")
}

/// The lines KSS writes before a program's `DEF` (KUKA System Software 8, "the file's
/// attributes"): read-write access for the expert and operator (`&ACCESS RVP`), release 1, the
/// template it was made from and the edit mask (`*`: every line editable).
pub(crate) const KSS_HEADER: &str =
    "&ACCESS RVP\n&REL 1\n&PARAM TEMPLATE = C:\\KRC\\Roboter\\Template\\vorgabe\n&PARAM EDITMASK = *\n";

/// What a KRL program holds and how it writes it: `CIRC` with Cartesian targets, up to six
/// external axes `E1` to `E6`, the carrier's then the positioner's, in its `E6POS`/`E6AXIS` (KUKA System Software 8.x
/// operating and programming instructions), the process words in `$` system variables.
static WRITING: Writing = Writing {
    lines_per_file: None,
    routine_prefix: "",
    states_mass: false,
    cartesian: true,
    pulses: false,
    arcs: Some(Arcs {
        form: Form::ViaEnd,
        joint_targets: false,
    }),
    carrier: ExternalGroup {
        most: 6,
        form: "E1 to E6",
    },
    positioner: ExternalGroup {
        most: 6,
        form: "E1 to E6",
    },
    process: Some(&super::process::FORM),
};

impl Generator for super::Krl {
    fn header(&self, plan: &Plan, _main: &str, _subs: &[String]) -> String {
        header(plan)
    }
    fn body(&self, plan: &Plan, part: &Part, _warnings: &mut Vec<String>) -> Result<String> {
        Ok(body(plan, part))
    }
    fn calls(&self, subs: &[String]) -> String {
        calls(subs)
    }
    fn wrap(&self, name: &str, header: &str, body: &str, _main: bool, _date: Stamp) -> String {
        wrap(name, header, body)
    }
    fn writing(&self) -> &'static Writing {
        &WRITING
    }
    fn data_file(&self, name: &str, text: &str) -> Option<(String, String)> {
        Some(super::data::split(name, text))
    }
}
