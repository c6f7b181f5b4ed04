//! The user and tool frames a FANUC controller holds by number, from its backup's
//! `SYSFRAME.VA` ([`super::va`]): `$MNUFRAME[1,n]`, user frame `n` of motion group 1 in the
//! controller's world, and `$MNUTOOL[1,n]`, tool frame `n` in its faceplate frame, each `X`,
//! `Y`, `Z` (mm) and `W`, `P`, `R` (deg, `Rz(R) Ry(P) Rx(W)`, as an LS position's). A position
//! in frame `n` the file gives takes it ([`Frame::Held`]); an entry `Uninitialized` gives none.

use super::va::{entries, Value};
use crate::program::cartesian::Frame;
use crate::program::{Context, JointTarget};
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use std::collections::BTreeMap;
use stiffid_core::{Error, Result};

/// The file's name in a backup.
pub(crate) const FILE: &str = "SYSFRAME.VA";

/// Frames by number: the frame and where the file states it.
type Held = BTreeMap<u32, (Isometry3<f64>, String)>;

/// The Cartesian `targets` with each user and tool frame the `context`'s backup's `SYSFRAME.VA` gives by
/// number held ([`Frame::Held`]); as they are without a backup or without the file.
///
/// # Errors
/// [`Error::Parse`] naming the file and line of an entry that is neither `Uninitialized` nor
/// six finite numbers `X:` to `R:` (a file cut off or edited), or a position in joint form.
pub(super) fn apply(context: &Context, targets: &mut [JointTarget]) -> Result<()> {
    let Some(file) = super::va::the_file(context, FILE)? else {
        return Ok(());
    };
    if !["$MNUFRAME", "$MNUTOOL"]
        .iter()
        .any(|v| super::va::declares(file.1, v))
    {
        return Err(Error::Parse {
            source_name: file.0.to_string(),
            message: format!("holds neither $MNUFRAME nor $MNUTOOL (empty, cut off, or another file): expected the ASCII variable file a controller's backup writes beside SYSFRAME.SV, its user and tool frames under '[*SYSTEM*]$MNUFRAME ..' and '[*SYSTEM*]$MNUTOOL ..'; give the backup's {FILE}"),
        });
    }
    let (users, tools) = (held(file, "$MNUFRAME")?, held(file, "$MNUTOOL")?);
    for c in targets
        .iter_mut()
        .filter_map(|t| t.cartesian.as_deref_mut())
    {
        c.frame = taken(&c.frame, &users);
        c.tool = taken(&c.tool, &tools);
    }
    Ok(())
}

/// The frame `frame` of a position, held where it is one by number the file gives.
fn taken(frame: &Frame, held: &Held) -> Frame {
    match frame {
        Frame::Numbered(line, n) => match held.get(n) {
            Some((f, source)) => Frame::Held(*line, *n, *f, source.clone()),
            None => frame.clone(),
        },
        other => other.clone(),
    }
}

/// The frames of motion group 1 of variable `variable` in `file`, by number.
fn held((name, text): (&str, &str), variable: &str) -> Result<Held> {
    let mut out = Held::new();
    let failed = |line: u64, message: String| Error::Parse {
        source_name: name.to_string(),
        message: format!("line {line}: {message}"),
    };
    for e in entries(text, variable) {
        let p = match e.value.map_err(|(line, why)| failed(line, why))? {
            Some(Value::Cartesian(p, _)) => p,
            Some(Value::Joint(_)) => return Err(failed(e.line, format!("{variable}[{},{}]: a position in joint form; stiffid reads these frames as X, Y, Z, W, P, R", e.group, e.number))),
            None => continue,
        };
        if e.group != 1 {
            continue;
        }
        let rotation = UnitQuaternion::from_euler_angles(
            p[3].to_radians(),
            p[4].to_radians(),
            p[5].to_radians(),
        );
        let position = Translation3::new(p[0] * 1e-3, p[1] * 1e-3, p[2] * 1e-3);
        let frame = Isometry3::from_parts(position, rotation);
        let source = format!("{name} line {} ({variable}[1,{}])", e.line, e.number);
        out.insert(e.number, (frame, source));
    }
    Ok(out)
}
