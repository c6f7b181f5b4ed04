//! `stiffid schema` (hidden): the JSON Schema (draft 2020-12) of every JSON document stiffid
//! writes, generated from the types that write them; the repository ships them in
//! `docs/schemas/NAME.schema.json` and a test keeps those equal to this command's output.

use crate::output::{self, json};
use anyhow::{bail, Result};
use schemars::generate::SchemaSettings;
use schemars::transform::RecursiveTransform;
use schemars::{JsonSchema, Schema};
use stiffid::internal::io::stiffness::StiffnessFile;

/// Arguments of `stiffid schema`.
#[derive(clap::Args)]
pub struct Args {
    /// The document: one of the names `stiffid schema` lists.
    name: Option<String>,
}

/// Every document with a schema: its name and what writes (or reads) it.
const DOCUMENTS: [(&str, &str); 17] = [
    ("kinematics", "stiffid kinematics --json"),
    ("evaluate", "stiffid evaluate --json"),
    ("select", "stiffid select --json"),
    ("plan", "stiffid select --report DIR: plan.json"),
    ("predict", "stiffid predict --json"),
    (
        "identify",
        "stiffid identify --json (and --out): the six drives, a model with virtual springs, or --compare-models",
    ),
    ("stiffness", "the stiffness file --stiffness reads"),
    ("validate", "stiffid validate --json"),
    (
        "compensate",
        "stiffid compensate --json (and the report's summary.json)",
    ),
    (
        "simulate",
        "stiffid simulate --json (and --out DIR/simulation.json)",
    ),
    ("reproduce", "stiffid reproduce: summary.json"),
    ("register", "stiffid register --json"),
    ("register-postures", "stiffid register --count N --json"),
    ("calibrate-cell", "stiffid calibrate-cell --json"),
    ("calibrate", "stiffid calibrate --json"),
    ("place", "stiffid place --json"),
    ("force", "stiffid force --json"),
];

/// Prints the schema of the named document, or without a name the names, one per line.
pub fn run(args: &Args) -> Result<()> {
    let Some(name) = &args.name else {
        let lines: Vec<String> = DOCUMENTS
            .iter()
            .map(|(name, what)| format!("{name:<12} {what}\n"))
            .collect();
        return output::print(&lines.concat());
    };
    output::print(&json(&schema(name)?)?)
}

/// The schema of the document `name` (see [`DOCUMENTS`]).
///
/// # Errors
/// An unknown name.
pub fn schema(name: &str) -> Result<Schema> {
    let Some((_, what)) = DOCUMENTS.iter().find(|(n, _)| *n == name) else {
        let names: Vec<&str> = DOCUMENTS.iter().map(|(n, _)| *n).collect();
        bail!("{name:?}: expected one of {}", names.join(", "));
    };
    let mut schema = match name {
        "kinematics" => closed::<stiffid::app::kinematics::document::Document<'static>>(),
        "evaluate" => closed::<stiffid::app::evaluate::Report>(),
        "select" => closed::<stiffid::app::select::document::Document>(),
        "plan" => closed::<stiffid::app::plan::Report>(),
        "predict" => closed::<stiffid::app::predict::document::Document<'static>>(),
        "identify" => closed::<stiffid::app::identify::document::Document<'static>>(),
        "validate" => closed::<stiffid::app::validate::document::Document<'static>>(),
        "compensate" => closed::<stiffid::app::compensate::document::Document<'static>>(),
        "place" => closed::<stiffid::app::place::document::Document<'static>>(),
        "force" => closed::<stiffid::app::force::Report>(),
        "simulate" => closed::<stiffid::app::simulate::Report>(),
        "reproduce" => closed::<stiffid::app::reproduce::document::Summary<'static>>(),
        "register" => closed::<stiffid::app::register::Report>(),
        "register-postures" => closed::<stiffid::app::register::document::Proposal<'static>>(),
        "calibrate-cell" => closed::<stiffid::app::calibrate_cell::Report>(),
        "calibrate" => closed::<stiffid::app::calibrate::document::Document<'static>>(),
        _ => open::<StiffnessFile>(),
    };
    schema.insert("title".into(), (*what).into());
    Ok(schema)
}

/// The schema of a document stiffid writes: every key required unless it may be left out, no
/// other keys (`additionalProperties: false` on every object with named keys).
fn closed<T: JsonSchema>() -> Schema {
    let close = |s: &mut Schema| {
        if s.get("properties").is_some() && s.get("additionalProperties").is_none() {
            s.insert("additionalProperties".into(), false.into());
        }
    };
    SchemaSettings::draft2020_12()
        .for_serialize()
        .with_transform(RecursiveTransform(close))
        .into_generator()
        .into_root_schema_for::<T>()
}

/// The schema of a document stiffid reads: other keys are allowed (and ignored).
fn open<T: JsonSchema>() -> Schema {
    SchemaSettings::draft2020_12()
        .for_deserialize()
        .into_generator()
        .into_root_schema_for::<T>()
}
