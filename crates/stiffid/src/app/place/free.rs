//! `place --free`: the part's height and tilt free besides x, y and the rotation, in the
//! grammar of `compensate --free` ([`stiffid_machining::compensate::grammar`]).

use super::{Free, Region};
use stiffid_core::common::words::number;
use stiffid_core::Result;
use stiffid_machining::compensate::grammar::{invalid, parts};

/// What `place --free` takes, for its errors.
const EXPECTED: &str = "expected z (the part's height: z=LO..HI, mm from its own, default -100..100) or tilt (about the base x and y axes: tilt=-T..T, deg, default -10..10); x, y and the rotation are always free (--region-mm, --rotation-deg)";

impl Free {
    /// The height and tilt freed by `texts` (`place --free`, Python's `place(free=[...])`): `z` or
    /// `z=LO..HI` (the part origin's height from its own `own_z`, m, within `LO..HI` mm; default
    /// +-100 mm) and `tilt` or `tilt=-T..T` (the tilt about the base x and y axes within +-T deg,
    /// `0 < T <= 45`; default 10 deg), each at most once; a variable not
    /// given stays at its own (the height `own_z`, no tilt). `None` when `texts` is empty: x, y and
    /// the rotation alone.
    ///
    /// # Errors
    /// [`stiffid_core::Error::InvalidOption`] ([`stiffid_core::JobOption::Free`]) naming the text:
    /// another name, a variable given twice, a step (the search is continuous), a tilt's range not
    /// symmetric or beyond its limit, a height's beyond +-20 m; and those of the grammar
    /// ([`parts`]).
    pub fn parse<S: AsRef<str>>(texts: &[S], own_z: f64) -> Result<Option<Free>> {
        if texts.is_empty() {
            return Ok(None);
        }
        let (mut z, mut tilt) = (None, None);
        for text in texts.iter().map(AsRef::as_ref) {
            let p = parts(text)?;
            if p.step.is_some() {
                return Err(invalid(
                    text,
                    "no step: the placement's search is continuous",
                ));
            }
            let slot = match p.name {
                "z" => &mut z,
                "tilt" => &mut tilt,
                _ => return Err(invalid(text, EXPECTED)),
            };
            if slot.is_some() {
                return Err(invalid(text, "given twice: at most one of each variable"));
            }
            *slot = Some(p.range);
        }
        let h = Region::DEFAULT_HEIGHT_MM;
        let [lo, hi] = z.flatten().unwrap_or([-h, h]);
        let most = Region::MAX_EXTENT_M * 1e3;
        if lo < -most || hi > most {
            return Err(invalid(
                &format!("z={}..{}", number(lo), number(hi)),
                &format!("expected a range within -{0}..{0} mm", number(most)),
            ));
        }
        let t = match tilt.flatten() {
            None => Region::DEFAULT_TILT_DEG,
            Some([lo, hi]) if hi > 0.0 && lo == -hi && hi <= Region::MAX_TILT_DEG => hi,
            Some([lo, hi]) => {
                return Err(invalid(
                    &format!("tilt={}..{}", number(lo), number(hi)),
                    &format!(
                        "expected a range -T..T, 0 < T <= {} deg",
                        number(Region::MAX_TILT_DEG)
                    ),
                ))
            }
        };
        Ok(Some(Free {
            z: match z {
                Some(_) => [own_z + lo * 1e-3, own_z + hi * 1e-3],
                None => [own_z, own_z],
            },
            tilt: match tilt {
                Some(_) => t.to_radians(),
                None => 0.0,
            },
        }))
    }
}
