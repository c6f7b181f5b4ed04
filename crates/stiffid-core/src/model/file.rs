//! The setup file's `[model]` table: virtual springs by axis or by family, and the fragment
//! written back for a chosen model.
//!
//! ```toml
//! [[model.spring]]
//! name = "elbow_bend"
//! kind = "rotation"                 # or "translation"
//! link = 3                          # 0 the base, 1..6 the link after joint k
//! axis = [1, 0, 0]                  # in link k's frame (normalised)
//! point_mm = [0, 0, 0]              # rotation only: a point of the axis, link frame (default origin)
//! nominal_stiffness_nm_per_rad = 5e6   # rotation; a translation takes nominal_stiffness_n_per_mm
//! candidate = false                 # true: not in the model, a candidate of --compare-models
//! law = "linear"                    # candidates only: "lost-motion" or "load-dependent" (super::Law)
//!
//! [[model.family]]
//! family = "tilt"                   # tilt, tool, base or carriage (crate::model::Family)
//! links = [2, 3]                    # tilt only: its joints
//! nominal_stiffness_nm_per_rad = 5e6   # of its rotational springs
//! nominal_stiffness_n_per_mm = 1e4     # of its translational springs
//! ```
//! Springs come first, in file order, then the families'. A spring with `candidate = true` is not
//! part of the model: it joins the candidates of `stiffid identify --compare-models`
//! (`stiffid_identify::compare`), by default and by name.

use super::{unit_axis, Family, Kind, Spring};
use crate::{Error, Result, Robot};
use nalgebra::Vector3;
use serde::Deserialize;
use std::fmt::Write;

/// The `[model]` table as written.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(crate) struct ModelFile {
    #[serde(default)]
    spring: Vec<SpringFile>,
    #[serde(default)]
    family: Vec<FamilyFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpringFile {
    name: String,
    kind: Kind,
    link: usize,
    #[serde(deserialize_with = "crate::common::exact::array")]
    axis: [f64; 3],
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    point_mm: Option<[f64; 3]>,
    nominal_stiffness_nm_per_rad: Option<f64>,
    nominal_stiffness_n_per_mm: Option<f64>,
    #[serde(default)]
    candidate: bool,
    #[serde(default)]
    law: LawFile,
}

/// A spring's `law` as written.
#[derive(Debug, Deserialize, Default, Clone, Copy, PartialEq)]
#[serde(rename_all = "kebab-case")]
enum LawFile {
    #[default]
    Linear,
    LostMotion,
    LoadDependent,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FamilyFile {
    family: String,
    #[serde(default)]
    links: Vec<usize>,
    nominal_stiffness_nm_per_rad: Option<f64>,
    nominal_stiffness_n_per_mm: Option<f64>,
}

fn invalid(field: String, message: &str) -> Error {
    Error::InvalidField {
        field,
        message: message.to_string(),
    }
}

/// The springs of a `[model]` table: those of the model and the declared candidates.
#[derive(Debug, Clone, Default)]
pub(crate) struct Springs {
    /// The model's virtual springs, in file order, then the families'.
    pub model: Vec<Spring>,
    /// The springs with `candidate = true`, in file order.
    pub candidates: Vec<Spring>,
}

impl ModelFile {
    /// The virtual springs on `robot`, SI units, checked together in file order (the candidates
    /// among them: names unique over both) by `super::check_springs`, so that an error names
    /// the file's `model.spring[i]`.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the field: a zero or non-finite axis, a point or a stiffness
    /// in the other kind's unit, an unknown family or bad family links, and those of
    /// `super::check_springs`.
    pub(crate) fn springs(&self, robot: &Robot) -> Result<Springs> {
        let mut out = Vec::new();
        for (i, s) in self.spring.iter().enumerate() {
            let field = |f: &str| format!("model.spring[{}].{f}", i + 1);
            let axis = unit_axis(Vector3::from(s.axis), &field("axis"))?;
            let (stiffness, other) = match s.kind {
                Kind::Rotation => (
                    s.nominal_stiffness_nm_per_rad,
                    ("nominal_stiffness_n_per_mm", s.nominal_stiffness_n_per_mm),
                ),
                Kind::Translation => (
                    s.nominal_stiffness_n_per_mm.map(|k| k * 1e3),
                    (
                        "nominal_stiffness_nm_per_rad",
                        s.nominal_stiffness_nm_per_rad,
                    ),
                ),
            };
            if other.1.is_some() {
                return Err(invalid(field(other.0), "not for this kind of spring: a rotation takes nominal_stiffness_nm_per_rad, a translation nominal_stiffness_n_per_mm"));
            }
            if s.kind == Kind::Translation && s.point_mm.is_some() {
                return Err(invalid(
                    field("point_mm"),
                    "a translation has no point: give only its direction (axis)",
                ));
            }
            let law = match s.law {
                LawFile::Linear => super::Law::Linear,
                LawFile::LostMotion => super::Law::LostMotion {
                    smoothing: super::DEFAULT_SMOOTHING,
                },
                LawFile::LoadDependent => super::Law::LoadDependent,
            };
            if !law.is_linear() && !s.candidate {
                return Err(invalid(field("law"), "a lost-motion or load-dependent joint can only be a candidate (candidate = true): prediction, compensation and the design criteria take every spring as linear"));
            }
            out.push(Spring {
                name: s.name.clone(),
                kind: s.kind,
                link: s.link,
                axis,
                point: s
                    .point_mm
                    .map_or(Vector3::zeros(), |p| Vector3::from(p) * 1e-3),
                nominal_stiffness: stiffness,
                law,
            });
        }
        for (i, f) in self.family.iter().enumerate() {
            let field = |n: &str| format!("model.family[{}].{n}", i + 1);
            let family = Family::parse(&f.family, &field("family"))?;
            out.extend(family.springs(
                robot,
                &f.links,
                f.nominal_stiffness_nm_per_rad,
                f.nominal_stiffness_n_per_mm.map(|k| k * 1e3),
                &field("links"),
            )?);
        }
        super::check_springs(&out)?;
        let declared = self.spring.len();
        let is_candidate = |i: usize| i < declared && self.spring[i].candidate;
        let (candidates, model): (Vec<_>, Vec<_>) = out
            .into_iter()
            .enumerate()
            .partition(|(i, _)| is_candidate(*i));
        Ok(Springs {
            model: model.into_iter().map(|(_, s)| s).collect(),
            candidates: candidates.into_iter().map(|(_, s)| s).collect(),
        })
    }
}

/// The virtual springs of a setup file's `[model]` table given alone (`[[model.spring]]` and
/// `[[model.family]]` tables, e.g. what [`fragment`] writes), on `robot`, SI units; an empty
/// text is no spring.
///
/// # Errors
/// [`Error::Parse`] naming `source_name` for TOML that is not a `[model]` table alone; those of
/// the setup file's `[model]` table ([`Error::InvalidField`] naming the field, e.g.
/// `model.spring[1].axis`), and a spring with `candidate = true` (candidates belong in the setup
/// file). The springs are checked together when a setup is built with them.
pub fn parse(text: &str, source_name: &str, robot: &Robot) -> Result<Vec<Spring>> {
    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Fragment {
        #[serde(default)]
        model: ModelFile,
    }
    let f: Fragment = toml::from_str(text).map_err(|e| Error::Parse {
        source_name: source_name.to_string(),
        message: crate::common::limits::one_line(&e.to_string()),
    })?;
    if let Some(i) = f.model.spring.iter().position(|s| s.candidate) {
        return Err(invalid(
            format!("model.spring[{}].candidate", i + 1),
            "a model fragment gives the model's springs: declare candidates in the setup file",
        ));
    }
    Ok(f.model.springs(robot)?.model)
}

/// The `[model]` fragment of a setup file that gives `springs` (every spring written with its axis,
/// so the fragment does not depend on the families' definitions; nominal stiffness as given). A
/// joint of a nonlinear law ([`super::Law`]) is written as a comment: a model holds springs only.
pub fn fragment(springs: &[Spring]) -> String {
    let mut s = String::new();
    for spring in springs.iter().filter(|s| !s.law.is_linear()) {
        let _ = writeln!(
            s,
            "# '{}' ({}) is chosen too: a model holds linear springs only, so it is left out here.\n",
            spring.name,
            match spring.law {
                super::Law::LostMotion { .. } => "a lost motion",
                _ => "a load-dependent compliance",
            }
        );
    }
    for spring in springs.iter().filter(|s| s.law.is_linear()) {
        let a = spring.axis;
        let kind = match spring.kind {
            Kind::Rotation => "rotation",
            Kind::Translation => "translation",
        };
        let _ = writeln!(s, "[[model.spring]]");
        let _ = writeln!(s, "name = \"{}\"", spring.name);
        let _ = writeln!(s, "kind = \"{kind}\"");
        let _ = writeln!(s, "link = {}", spring.link);
        let _ = writeln!(s, "axis = [{:?}, {:?}, {:?}]", a.x, a.y, a.z);
        if spring.kind == Kind::Rotation {
            let p = spring.point * 1e3;
            let _ = writeln!(s, "point_mm = [{:?}, {:?}, {:?}]", p.x, p.y, p.z);
        }
        if let Some(k) = spring.nominal_stiffness {
            let unit = spring.kind.stiffness_unit();
            let _ = writeln!(
                s,
                "nominal_stiffness_{} = {:?}",
                unit.suffix(),
                k * unit.per_si()
            );
        }
        s.push('\n');
    }
    s
}
