//! `stiffid calibrate`: the robot's geometric errors, gravity terms, the tracker's registration
//! and the measuring points fitted together from unloaded readings
//! ([`stiffid::app::calibrate`]), with held-out validation, and the calibrated robot
//! written as a robot file and a URDF.

use crate::load;
use crate::output::{self, print_json_or, OutFile};
use crate::progress::Bars;
use crate::report::calibration;
use anyhow::{bail, Result};
use std::path::PathBuf;
use stiffid::app::calibrate::document::{Document, Parameter};
use stiffid::app::calibrate::GravitySpec;
use stiffid::app::calibrate::{self as job, Tolerances};
use stiffid::app::document::mm;
use stiffid::app::readings::Request as Readings;
use stiffid::internal::metrology::calibration::identifiability::CORRELATION_INSEPARABLE;
use stiffid::internal::metrology::calibration::maps::Spec;
use stiffid::internal::metrology::calibration::Geometry;

use crate::commands::common::{choice, Common};

/// Arguments of `stiffid calibrate`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Readings CSV: posture,point,q1_deg..q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm (or
    /// x_mm,y_mm,z_mm in the base frame), one row per posture and measuring point (at most 100000
    /// rows); with load steps (load_step or load_n and the force columns), the loaded readings
    /// fit the setup's model's compliances in the same fit.
    #[arg(long)]
    data: PathBuf,
    /// The joint errors fitted: none (the tracker and the measuring points only, as
    /// calibrate-cell), offsets (the joint angle offsets too) or full (every joint error, the
    /// dependent ones merged).
    #[arg(long, value_parser = choice::<Geometry>(), default_value = "full")]
    geometry: Geometry,
    /// The deflection under the robot's own weight: auto (chosen with --maps by a
    /// cross-validation that holds out groups of postures: the simplest model within one standard
    /// error of the best, with 10 distinct postures or more; none below), none, arm (three terms:
    /// the upper arm's and the forearm's weight on joints 2 and 3, on an anthropomorphic arm),
    /// masses (the robot's link masses and centres known, the joint compliances fitted), lumped (compliance
    /// times mass moment of the upper arm, the forearm and the wrist) or lumped-links (of every
    /// link each joint carries).
    #[arg(long, value_parser = choice::<GravitySpec>(), default_value = "auto")]
    gravity: GravitySpec,
    /// The bound on the gravity terms, mrad [0.0001 to 100]: each term is fitted with a
    /// Gaussian prior centred on its nominal value whose standard deviation deflects its joint
    /// by this much at the largest torque it meets within the robot's joint limits, the same for
    /// every gravity model, chosen by --gravity auto or given.
    #[arg(long, default_value = "3")]
    gravity_bound_mrad: f64,
    /// Held-out readings CSV (same format): their 3D position error with the calibration.
    #[arg(long)]
    validate: Option<PathBuf>,
    /// Register the tracker anew on the --validate readings (another series: the tracker moved).
    #[arg(long, requires = "validate")]
    reregister: bool,
    /// The level of the --validate readings' prediction intervals [0.5 to 0.999], default
    /// 0.95: jackknife+ over the fitted postures (one fold each, at most 5000), built from their
    /// leave-one-posture-out errors; the document's validation reports each reading's interval
    /// and the share of held-out coordinates inside (coverage).
    #[arg(long)]
    level: Option<f64>,
    /// Update a calibrated robot from a check campaign (--data, at least 5 postures; `select
    /// --for check` designs about 10): the setup's robot is the calibrated robot file, and only
    /// what drifts between sessions is refitted, by default (a bare --update) offsets,base,tool:
    /// the joint angle offsets, the tracker's registration (the base) and the measuring points
    /// (the tool); add gravity to refit the gravity terms of --stiffness, external (a cell with
    /// a track or a positioner) to refit the external axes' zero offsets; leave out offsets or
    /// tool to keep them (base is always refitted). The DH table, error maps, axis map, the
    /// track's direction and error motions, the positioner's axis lines and the --stiffness
    /// file's gravity terms are kept in the forward model. A list the check
    /// readings cannot identify is refused, naming what merges. First the check: each reading's
    /// error with the calibrated robot against the bound of its calibration's held-out errors
    /// ([held_out], at --level), and whether the robot drifted beyond it. --out writes the
    /// updated robot file.
    #[arg(long, value_name = "LIST", num_args = 0..=1, default_missing_value = "offsets,base,tool", conflicts_with_all = ["geometry", "gravity", "maps", "error_motions"])]
    update: Option<String>,
    /// With --update: the stiffness file of the robot's calibration (calibrate --stiffness-out):
    /// its gravity terms (the sag under the robot's own weight) are kept in the update's
    /// forward model, or refitted from there with gravity in the --update list.
    #[arg(long, requires = "update")]
    stiffness: Option<PathBuf>,
    /// Fit readings that no rigid transform explains (a mirror image of the robot's points, or a
    /// residual beyond the larger of 10 mm and 1000 times the tracker noise) instead of refusing
    /// them.
    #[arg(long)]
    force: bool,
    /// Leave-one-posture-out: each posture's error predicted by the fit of the others, one
    /// Gauss-Newton step from the full fit (at most 5000 postures, with progress on stderr).
    #[arg(long)]
    cross_validate: bool,
    /// Nominal tolerance of the joints' length errors, mm [1e-6 to 1000] (a prior: weakly
    /// determined errors are pulled towards nominal); with --tolerance-deg.
    #[arg(long, requires = "tolerance_deg")]
    tolerance_mm: Option<f64>,
    /// Nominal tolerance of the joints' angle errors, deg [1e-6 to 90]; with --tolerance-mm.
    #[arg(long, requires = "tolerance_mm")]
    tolerance_deg: Option<f64>,
    /// The joint error maps fitted (each axis's angle error as a Fourier series of its own
    /// angle): auto (joints, harmonics and ridge chosen by cross-validation inside the readings,
    /// with 30 distinct postures or more; none below), none, or joints with their harmonics,
    /// J1,J3:16 (a bare joint 16 harmonics; the ridge chosen by cross-validation). With the
    /// readings' directions (dir1..dir6) a b adds the joint's backlash term (J2:8b; J2:b the
    /// backlash alone), and auto considers one per joint.
    #[arg(long, default_value = "auto")]
    maps: String,
    /// With a track (the setup's carrier axes): the order of the polynomials of its six error
    /// motions along the travel, auto (chosen by cross-validation over the readings' postures)
    /// or an order 0 to 8 (0: its direction alone).
    #[arg(long, default_value = "auto")]
    error_motions: String,
    /// Write the calibrated robot file here (robot TOML: the DH table with the errors, the axis
    /// map; point a setup's `robot` at it), the tracker and measuring-point fragment of the setup
    /// in comments at its end. Never over an input.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the calibrated robot as a URDF here (corrected joint origins).
    #[arg(long)]
    urdf_out: Option<PathBuf>,
    /// With loaded readings (load steps) or --gravity: write the fitted compliances as a
    /// stiffness file here (JSON, as identify --out; predict and compensate --stiffness read
    /// it): the fitted parameters at their fitted value, the others at the setup's nominal
    /// stiffness, and the fitted gravity terms (compensate adds the sag under the robot's own
    /// weight). Never over an input.
    #[arg(long)]
    stiffness_out: Option<PathBuf>,
    /// Also write a report into this directory (created; must be missing, empty or hold an
    /// earlier calibration report): each reading's error before and after, the errors in 3D,
    /// the parameters with their intervals, the residuals against the noise, the merged
    /// parameters.
    #[arg(long)]
    report: Option<PathBuf>,
}

/// Runs `stiffid calibrate`.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let path = &args.data;
    let priors = match (args.tolerance_mm, args.tolerance_deg) {
        (Some(l), Some(a)) => Some(Tolerances::from_mm_deg(l, a)?),
        _ => None,
    };
    let content = load::read(path)?;
    let held = match &args.validate {
        Some(p) => Some(load::read(p)?),
        None => None,
    };
    let out = prepare(&args.out, "--out")?;
    let urdf_out = prepare(&args.urdf_out, "--urdf-out")?;
    let stiffness_out = prepare(&args.stiffness_out, "--stiffness-out")?;
    let bars = Bars::new(false);
    let report_dir = args.report.as_deref().map(calibration::open).transpose()?;
    let request = job::Request {
        readings: Readings {
            setup: &setup,
            setup_name: args.common.setup.clone(),
            name: path.display().to_string(),
            text: &content,
            force: args.force,
        },
        geometry: args.geometry,
        gravity: args.gravity,
        gravity_bound: Some(args.gravity_bound_mrad * 1e-3),
        validate: (args.validate.as_ref().zip(held.as_deref()))
            .map(|(p, t)| (p.display().to_string(), t)),
        reregister: args.reregister,
        cross_validate: args.cross_validate,
        priors,
        progress: &bars,
        maps: Spec::parse(&args.maps)?,
        error_motions: stiffid::internal::metrology::calibration::motions::Spec::parse(
            &args.error_motions,
        )?,
        level: args.level,
        update: args.update.is_some(),
        refit: (args.update.as_deref().map(job::Refits::parse))
            .transpose()?
            .unwrap_or_default(),
        weight: match &args.stiffness {
            Some(p) => load::stiffness(p, &setup)?.own_weight,
            None => None,
        },
        urdf: args.urdf_out.is_some(),
    };
    let report = job::run(&request)?.report;
    let document = report.document();
    // Checked before anything is written.
    let stiffness_text = match (&stiffness_out, document.stiffness_file_out()) {
        (None, _) => None,
        (Some(_), Some(text)) => Some(text),
        (Some(_), None) => bail!(
            "--stiffness-out: {}",
            document.stiffness_file_error.map(String::from).unwrap_or_else(|| {
                "no compliance is fitted: loaded readings (load steps) or a gravity model (--gravity masses, lumped, lumped-links or arm) fit them"
                    .into()
            })
        ),
    };
    let robot_text = match (&out, document.robot_file_out()) {
        (Some(_), None) => bail!("--out: {}", document.robot_file_error.unwrap_or_default()),
        (_, text) => text,
    };
    let urdf_text = match (&urdf_out, document.urdf) {
        (Some(_), None) => bail!("--urdf-out: {}", document.urdf_error.unwrap_or_default()),
        (_, text) => text,
    };
    if let Some((o, text)) = out.as_ref().zip(robot_text) {
        o.write(text.as_bytes())?;
    }
    if let Some((o, text)) = stiffness_out.as_ref().zip(stiffness_text) {
        o.write(text.as_bytes())?;
    }
    if let Some((o, text)) = urdf_out.as_ref().zip(urdf_text) {
        o.write(text.as_bytes())?;
    }
    if let Some(dir) = report_dir {
        calibration::write(dir, &setup, &document)?;
    }
    output::warnings(document.warnings);
    print_json_or(args.common.json, &document, text_of)?;
    // A drifted robot fails the check's gate, after its update is written.
    if let Some(check) = document.check {
        output::staged::commit()?;
        check.gate()?;
    }
    Ok(())
}

fn prepare(path: &Option<PathBuf>, option: &str) -> Result<Option<OutFile>> {
    path.as_ref()
        .map(|p| OutFile::prepare(p, option))
        .transpose()
}

/// The nominal robot's baseline as what it is: registered on the readings in the tracker's
/// frame, as it is in the base frame (nothing registered).
fn nominal_label(measured_in: &str) -> &'static str {
    match measured_in {
        "base" => "nominal, base frame, nothing registered",
        _ => "nominal, tracker registered",
    }
}

/// The note under the parameters' table for those the readings do not separate (correlated
/// beyond 0.999 in absolute value): their standard deviations are not printed.
fn inseparable_text(d: &Document) -> String {
    let names: Vec<String> = (d.parameters.iter())
        .filter(|p| p.identified && !p.inseparable_from.is_empty())
        .map(|p| format!("{} (with {})", p.name, p.inseparable_from.join(", ")))
        .collect();
    match names.is_empty() {
        true => String::new(),
        false => format!(
            "inseparable: {}: correlated beyond 0.999, the readings determine only a combination of them, so no standard deviation of one alone is printed; readings at other postures (or loads) separate them\n",
            names.join("; ")
        ),
    }
}

/// The note under the parameters' table on the gravity terms the robot file states: in SI
/// (the table's value times 1e-6) and in the link frames of its DH table, each term whose file
/// value is not the table's so converted named with both.
fn gravity_file_text(d: &Document) -> String {
    let terms: Vec<_> = (d.parameters.iter())
        .filter(|p| p.identified)
        .filter_map(|p| p.robot_file_si.map(|si| (p, si)))
        .collect();
    if terms.is_empty() {
        return String::new();
    }
    let mut text = "gravity terms: the robot file's [gravity] states them in SI, value_si = the value above x 1e-6".to_string();
    let turned: Vec<String> = (terms.iter())
        .filter(|(p, si)| (p.value * 1e-6 - si).abs() > 1e-9 * si.abs().max(p.value.abs() * 1e-6))
        .map(|(p, si)| {
            format!(
                "{} = {} {} here, value_si = {si:e} in the file",
                p.name, p.value, p.unit
            )
        })
        .collect();
    match turned.is_empty() {
        true => text += "\n",
        false => {
            text += ", and the first moments in the link frames of its DH table, turned from the fit's: ";
            text += &turned.join("; ");
            text += "\n";
        }
    }
    text
}

fn text_of(d: &Document) -> String {
    let mut text = format!(
        "robot calibration from {} readings (setup {}, geometry {}, gravity {}{}, {} iterations)\n\
         residual RMS {:.4} mm ({}: {:.4} mm); noise per coordinate {:.4} mm{}\n\
         rank {} of {} parameters, condition number {}\n",
        d.readings,
        d.setup,
        d.geometry,
        d.gravity,
        d.gravity_prior.map_or(String::new(), |b| format!(
            " bounded by {} mrad",
            stiffid::internal::common::words::number(b * 1e3)
        )),
        d.iterations,
        mm(d.residual_rms),
        nominal_label(d.measured_in),
        mm(d.nominal_rms),
        mm(d.noise_std),
        d.noise_ratio
            .map_or(String::new(), |r| format!(" ({r:.2} x the setup's)")),
        d.rank,
        d.parameters.len(),
        d.condition.map_or("-".into(), |c| format!("{c:.3e}")),
    );
    text += "\nparameter          unit          nominal          value             sd\n";
    for p in (d.parameters.iter()).filter(|p| p.identified && harmonic(p).is_none()) {
        let sd = match (p.sd, p.inseparable_from.is_empty()) {
            (_, false) => "inseparable".into(),
            (Some(s), true) => format!("{s:.6}"),
            (None, true) => "-".into(),
        };
        text += &format!(
            "{:<18} {:<13} {:>12.6} {:>14.6} {:>14}\n",
            p.name, p.unit, p.nominal, p.value, sd
        );
    }
    text += &map_coefficients_text(d);
    text += &inseparable_text(d);
    text += &gravity_file_text(d);
    if !d.merged.is_empty() {
        text += "\nmerged (left nominal):\n";
        for m in &d.merged {
            let into = match m.into.is_empty() {
                true => "no effect".to_string(),
                false => format!("into {}", m.into.join(", ")),
            };
            text += &format!("  {}: {into}\n", m.name);
        }
    }
    for c in &d.correlations {
        let inseparable = match c.rho.abs() > CORRELATION_INSEPARABLE {
            true => ": not separately identifiable",
            false => "",
        };
        text += &format!(
            "correlated: {} and {} ({:+.3}){inseparable}\n",
            c.a, c.b, c.rho
        );
    }
    text += &check_text(d.check);
    text += &ladder_text(d.ladder.as_ref());
    text += &maps_text(&d.maps);
    for v in d.validation.iter().chain(&d.cross_validation) {
        text += &format!(
            "\nheld out ({}): RMS {:.4} mm, max {:.4} mm over {} ({}: {:.4} mm)\n",
            v.data,
            mm(v.rms),
            mm(v.max),
            readings(v.errors.len()),
            nominal_label(d.measured_in),
            mm(v.nominal_rms)
        );
        if let (Some(within), Some(beyond)) = (v.within_range_rms, v.beyond_range_rms) {
            text += &format!(
                "  within the fitted postures' axis ranges: RMS {:.4} mm over {}; beyond them by more than 1 deg (extrapolated): RMS {:.4} mm over {}\n",
                mm(within),
                readings(v.errors.len() - v.beyond_range_readings),
                mm(beyond),
                v.beyond_range_readings
            );
        }
        if let Some(i) = &v.intervals {
            text += &format!(
                "  {}% prediction intervals ({}, {} folds): {:.1}% of {} held-out coordinates inside{}\n",
                percent(i.level),
                i.method,
                i.folds,
                i.coverage_pct,
                i.coordinates,
                i.median_width
                    .map_or(String::new(), |w| format!(", median width {:.4} mm", mm(w)))
            );
            if i.from_fit > 0 {
                text += &format!(
                    "  {} coordinates bounded from the fit (Gaussian: the held-out variance and the fit's covariance): the jackknife+ needs {} held-out values at this level, the {} fitted postures give fewer\n",
                    i.from_fit, i.held_out_needed, i.folds
                );
            }
        }
    }
    text + "\n" + d.fragment
}

/// `level` in percent, to the tenth where it has one (99.7, not 100).
fn percent(level: f64) -> String {
    let pct = 100.0 * level;
    match (pct - pct.round()).abs() < 1e-9 {
        true => format!("{pct:.0}"),
        false => format!("{pct:.1}"),
    }
}

/// The check's lines (`--update`): the bound, the readings outside it and the verdict.
fn check_text(c: Option<&stiffid::app::calibrate::drift::Check>) -> String {
    let Some(c) = c else {
        return String::new();
    };
    format!(
        "\ncheck before the update: {} of {} readings beyond {:.4} mm ({:.0}% bound of the calibration's {} held-out errors, {}): {:.1}% outside, an undrifted robot explains up to {}\n  {}\n",
        c.outside,
        c.readings,
        mm(c.bound),
        100.0 * c.level,
        c.held_out,
        c.source,
        100.0 * c.share_outside,
        c.allowed,
        match c.drifted {
            true => "drifted beyond its intervals: update it (--out)",
            false => "not drifted beyond its intervals",
        }
    )
}

/// The ladder's lines: each rung's held-out error over groups of postures, the one fitted.
fn ladder_text(ladder: Option<&stiffid::app::calibrate::document::LadderDocument>) -> String {
    let Some(l) = ladder else {
        return String::new();
    };
    let mut text = match l.folds {
        0 => "
model: not chosen (too few postures), the first rung fitted
"
        .to_string(),
        k => format!(
            "
model chosen by {k} groups of postures held out (RMS, mm):
"
        ),
    };
    for (i, r) in l.rungs.iter().enumerate() {
        let figure = match (&r.held_out_rms_mm, &r.skipped) {
            (Some(v), None) => format!("{v:.4}"),
            (Some(v), Some(why)) => format!("{v:.4}, skipped: {why}"),
            (None, Some(why)) => format!("skipped: {why}"),
            (None, None) => "-".into(),
        };
        text += &format!(
            "  {} gravity {:<12} {:<9} {figure}\n",
            if i == l.chosen { "*" } else { " " },
            r.gravity,
            if r.maps { "+ maps" } else { "" },
        );
    }
    let geometry = l.rungs.first().and_then(|r| r.held_out_rms_mm);
    let chosen = l.rungs.get(l.chosen).and_then(|r| r.held_out_rms_mm);
    if let (Some(g), Some(c), true) = (geometry, chosen, l.chosen > 0) {
        text += &format!("  chosen {c:.4} mm held out against {g:.4} mm for the geometry alone\n");
    }
    if l.folds > 0 {
        text += &format!("  why: {}\n", l.why);
    }
    if l.folds > 0 {
        let range: Vec<String> = (l.region_lower_deg.iter().zip(&l.region_upper_deg))
            .map(|(a, b)| format!("{a:.0}..{b:.0}"))
            .collect();
        text += &format!(
            "  spread judged where the robot is used: joints {} deg\n",
            range.join(", ")
        );
    }
    text
}

/// The maps' lines: the choice, the figure it was tuned on and the nested held-out gain.
fn maps_text(m: &stiffid::app::calibrate::document::MapsDocument) -> String {
    if let Some(why) = &m.skipped {
        return format!("\njoint error maps: none ({why})\n");
    }
    let mut text = format!(
        "\njoint error maps ({}): {}{}\n",
        m.asked,
        m.chosen,
        m.ridge.map_or(String::new(), |r| format!(", ridge {r:e}"))
    );
    if let (Some(a), Some(b)) = (m.inner_rms_mm, m.inner_none_rms_mm) {
        text += &format!(
            "  chosen by {}-posture cross-validation: {a:.4} mm held out ({b:.4} mm without maps; the figure the choice was tuned on)\n",
            m.postures
        );
    }
    if let Some(n) = &m.nested {
        text += &format!(
            "  nested ({} outer folds, the choice made inside each): {:.4} mm held out, {:.4} mm without maps\n",
            n.folds, n.rms_mm, n.none_rms_mm
        );
    }
    text
}

/// `n` readings, in words: `1 reading`, `2 readings`.
fn readings(n: usize) -> String {
    match n {
        1 => "1 reading".into(),
        n => format!("{n} readings"),
    }
}

/// A joint error map's harmonic coefficient (`joint3.map.cos12`): its map's name (`joint3.map`)
/// and its own (`cos12`).
fn harmonic(p: &Parameter) -> Option<(&str, &str)> {
    let (map, own) = p.name.split_once(".map.")?;
    (own.starts_with("cos") || own.starts_with("sin")).then(|| (&p.name[..map.len() + 4], own))
}

/// The fitted joint error maps' harmonic coefficients, a line per map (the parameter table would
/// list up to 128 a joint): their harmonics, the largest with its name, the range of their
/// standard deviations; each one is in `--json` and the calibrated robot file.
fn map_coefficients_text(d: &Document) -> String {
    let mut maps: Vec<(&str, Vec<&Parameter>)> = Vec::new();
    for p in d.parameters.iter().filter(|p| p.identified) {
        let Some((map, _)) = harmonic(p) else {
            continue;
        };
        match maps.iter_mut().find(|(m, _)| *m == map) {
            Some((_, ps)) => ps.push(p),
            None => maps.push((map, vec![p])),
        }
    }
    let mut text = String::new();
    for (map, ps) in &maps {
        let largest = (ps.iter()).max_by(|a, b| a.value.abs().total_cmp(&b.value.abs()));
        let sd = (ps.iter().filter_map(|p| p.sd)).fold((f64::INFINITY, 0.0f64), |(lo, hi), s| {
            (lo.min(s), hi.max(s))
        });
        let Some(largest) = largest else {
            continue;
        };
        text += &format!(
            "{map:<18} deg           {} harmonics, largest {:.6} ({}), sd {}\n",
            ps.len() / 2,
            largest.value,
            harmonic(largest).map_or("", |(_, own)| own),
            match sd.0.is_finite() {
                true => format!("{:.6} to {:.6}", sd.0, sd.1),
                false => "-".into(),
            }
        );
    }
    if !text.is_empty() {
        text += "(each map coefficient in --json and the calibrated robot file)\n";
    }
    text
}
