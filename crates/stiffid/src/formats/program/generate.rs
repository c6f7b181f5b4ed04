//! New robot programs from joint targets: what a G-code path becomes for a robot controller
//! ([`generate`]).
//!
//! Every target is a joint target (module docs of [`super`]: unambiguous, no configuration flags),
//! written as the dialect's joint motion with approximate positioning:
//! - KUKA KRL (`.src`): `DEF NAME( )`, `PTP {A1 .., ..., A6 ..} C_PTP` per target, `END`;
//! - ABB RAPID (`.mod`): `MODULE NAME`, `PROC main()`, `MoveAbsJ [[..],[9E9,..]], v100, z1,
//!   tool0;` per target;
//! - FANUC LS (`.ls`): `/PROG NAME`, `/MN` with `J P[i] 100% CNT100 ;` per target, `/POS` with
//!   each position in joint representation, `/END`.
//!
//! Between two targets the controller interpolates the axis angles, so the tool leaves the
//! straight line between them by the joint interpolation's deviation; dense targets (G-code arcs
//! split to their chord tolerance, straight moves written in short steps) keep it small. Speeds
//! and approximation are placeholders to set on the controller. Each written program reads back
//! ([`super::parse`]) to the same axis angles within `10^-DECIMALS` deg.

use super::{Dialect, DECIMALS};
use crate::{Error, Result};
use std::fmt::Write;

/// A program named `name` (letters, digits and `_`, starting with a letter; at most 24 characters)
/// in `dialect` that visits `q_deg` (axis angles q1..q6, deg) in order (module docs).
///
/// # Errors
/// [`Error::InvalidField`] (`name`) for a name the controllers do not accept, (`q_deg`) for no
/// target, more than [`super::MAX_TARGETS`] or a value that is not finite.
pub fn generate(dialect: Dialect, name: &str, q_deg: &[[f64; 6]]) -> Result<String> {
    let valid = name.len() <= 24
        && name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !valid {
        return Err(Error::InvalidField {
            field: "name".into(),
            message: format!("{name:?}: expected a program name of letters, digits and _, starting with a letter, at most 24 characters"),
        });
    }
    if q_deg.is_empty()
        || q_deg.len() > super::MAX_TARGETS
        || q_deg.iter().flatten().any(|v| !v.is_finite())
    {
        return Err(Error::InvalidField {
            field: "q_deg".into(),
            message: format!(
                "expected 1 to {} targets of 6 finite axis angles",
                super::MAX_TARGETS
            ),
        });
    }
    Ok(match dialect {
        Dialect::Krl => krl(name, q_deg),
        Dialect::Rapid => rapid(name, q_deg),
        Dialect::FanucLs => ls(name, q_deg),
    })
}

/// `x` with [`DECIMALS`] decimals, a negative zero without its sign.
fn v(x: f64) -> String {
    let s = format!("{x:.DECIMALS$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

fn krl(name: &str, q: &[[f64; 6]]) -> String {
    let mut s = format!("DEF {name}( )\n; written by stiffid: compensated joint targets\n");
    for t in q {
        let axes: Vec<String> = (0..6).map(|k| format!("A{} {}", k + 1, v(t[k]))).collect();
        let _ = writeln!(s, "PTP {{{}}} C_PTP", axes.join(", "));
    }
    s + "END\n"
}

fn rapid(name: &str, q: &[[f64; 6]]) -> String {
    let mut s = format!(
        "MODULE {name}\n  ! written by stiffid: compensated joint targets\n  PROC main()\n"
    );
    for t in q {
        let axes: Vec<String> = t.iter().map(|x| v(*x)).collect();
        let _ = writeln!(
            s,
            "    MoveAbsJ [[{}],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, z1, tool0;",
            axes.join(",")
        );
    }
    s + "  ENDPROC\nENDMODULE\n"
}

fn ls(name: &str, q: &[[f64; 6]]) -> String {
    let mut s = format!(
        "/PROG  {name}\n/ATTR\nCOMMENT\t\t= \"stiffid compensated\";\nDEFAULT_GROUP\t= 1,*,*,*,*;\n/MN\n"
    );
    for i in 1..=q.len() {
        let _ = writeln!(s, "{i:>4}:J P[{i}] 100% CNT100 ;");
    }
    s += "/POS\n";
    for (i, t) in q.iter().enumerate() {
        let _ = write!(
            s,
            "P[{}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {} deg,\tJ2= {} deg,\tJ3= {} deg,\n\tJ4= {} deg,\tJ5= {} deg,\tJ6= {} deg\n}};\n",
            i + 1,
            v(t[0]),
            v(t[1]),
            v(t[2]),
            v(t[3]),
            v(t[4]),
            v(t[5])
        );
    }
    s + "/END\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_dialect_reads_back_to_its_targets() {
        let q = [
            [0.0, -90.5, 12.25, 180.0, -45.123456789, 1e-9],
            [10.0, 20.0, -30.0, 40.0, 50.0, -360.0],
        ];
        for d in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
            let text = generate(d, "POCKET", &q).unwrap();
            let read = super::super::parse(&text, d).unwrap();
            assert_eq!(read.targets.len(), 2, "{d:?}");
            for (t, e) in read.targets.iter().zip(&q) {
                for (a, b) in t.q_deg.iter().zip(e) {
                    assert!((a - b).abs() <= 1e-9, "{d:?}: {:?}", t.q_deg);
                }
            }
        }
        assert!(generate(Dialect::Krl, "1x", &q).is_err());
        assert!(generate(Dialect::Krl, "P", &[]).is_err());
        assert!(generate(Dialect::Krl, "P", &[[f64::NAN; 6]]).is_err());
    }
}
