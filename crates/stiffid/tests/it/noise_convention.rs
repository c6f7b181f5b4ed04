//! One noise convention: `[noise] reading_sd_mm` is one coordinate of one tracker reading; a
//! displacement (loaded minus unloaded) has twice its variance; the old `variance_mm2` reads with
//! a warning that says what it meant; the model check of `identify` tests displacements built
//! from two noisy readings against twice the reading variance.

use crate::common::{paper_measurements, paper_with};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use stiffid::app::identify::{self, Options, Report, Request};
use stiffid::app::measurements::Data;
use stiffid::app::WarningKind;
use stiffid::internal::identify::adequacy::Verdict;
use stiffid::internal::setup::plausibility::warnings;
use stiffid::{internal::setup, Error, Setup};

const PAPER_NOISE: &str = "reading_sd_mm = 0.006793379129711516";

/// The paper's setup text with its `[noise]` line replaced by `noise` and `extra` appended.
fn paper_text(noise: &str, extra: &str) -> String {
    let text = setup::builtin_text("zhang2021-comau-nj165").unwrap();
    let line = text.lines().find(|l| l.starts_with(PAPER_NOISE)).unwrap();
    text.replace(line, noise) + extra
}

fn parse(text: &str) -> stiffid::Result<Setup> {
    setup::parse(text, "noise.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
}

#[test]
fn the_papers_displacement_variance_is_kept_to_the_bit() {
    let paper = setup::builtin("zhang2021-comau-nj165").unwrap();
    // What the paper's Table 3 gives, per displacement coordinate, as the old field read it.
    assert_eq!(paper.noise().displacement_variance(), 9.23e-5 * 1e-6);
    assert_eq!(paper.displacement_variance(), 9.23e-5 * 1e-6);
    assert_eq!(paper.noise().reading_variance, 9.23e-5 * 1e-6 / 2.0);
    assert!(warnings(&paper).is_empty());
}

#[test]
fn the_old_variance_reads_with_a_note_of_what_it_meant() {
    let new = parse(&paper_text("reading_sd_mm = 0.01", "")).unwrap();
    assert!((new.noise().reading_sd() - 1e-5).abs() < 1e-18);
    assert!((new.noise().displacement_variance() - 2e-10).abs() < 1e-24);
    // Without load steps the old field was a displacement's variance: half of it per reading.
    let old = parse(&paper_text("variance_mm2 = 2e-4", "")).unwrap();
    assert!((old.noise().reading_variance - 1e-10).abs() < 1e-24);
    let w = warnings(&old);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].kind, WarningKind::OldField);
    assert!(
        w[0].message.contains("one displacement")
            && w[0]
                .message
                .contains("reading_sd_mm = sqrt(variance_mm2 / 2) = 0.010000 mm"),
        "{}",
        w[0].message
    );
    // With load steps it was one reading's.
    let stepped =
        "[loading]\nload_n = 500.0\nanchor_mm = [2000.0, 1500.0, 0.0]\nsteps_n = [250.0, 500.0]\n";
    let text = paper_text("variance_mm2 = 2e-4", "");
    let start = text.find("[loading]").unwrap();
    let end = start + text[start..].find("\n\n").unwrap();
    let old_steps = parse(&(text[..start].to_string() + stepped + &text[end..])).unwrap();
    assert_eq!(old_steps.load_steps(), [250.0, 500.0]);
    assert!((old_steps.noise().reading_variance - 2e-10).abs() < 1e-24);
    let w = warnings(&old_steps);
    assert!(
        w.len() == 1 && w[0].message.contains("one reading (with loading.steps_n)"),
        "{w:?}"
    );
}

#[test]
fn one_noise_field_is_required_and_only_one() {
    let both = parse(&paper_text("reading_sd_mm = 0.01\nvariance_mm2 = 2e-4", ""));
    let neither = parse(&paper_text("", ""));
    let small = parse(&paper_text("reading_sd_mm = 1e-7", ""));
    for (result, field) in [
        (both, "noise.toml: noise.variance_mm2"),
        (neither, "noise.toml: noise.reading_sd_mm"),
        (small, "noise.toml: noise.reading_sd_mm"),
    ] {
        match result {
            Err(Error::InvalidField { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
    }
}

/// Displacements made of two readings, each with the setup's reading noise: the job's model
/// check finds them consistent (s about sqrt(2) times the reading sd), and would not against one
/// reading's variance.
#[test]
fn the_model_check_tests_displacements_against_two_readings() {
    let setup = paper_with("").unwrap();
    let sd = setup.noise().reading_sd();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let clean = paper_measurements(&setup);
    let data: Vec<_> = (0..10)
        .flat_map(|_| clean.clone())
        .map(|mut m| {
            let mut e = || sd * rng.sample::<f64, _>(StandardNormal);
            m.displacement += nalgebra::Vector3::from_fn(|_, _| e() - e());
            m
        })
        .collect();
    let report = identify::run(Request::<&[u8]> {
        progress: &(),
        setup_name: "setup".into(),
        setup: &setup,
        data: Data::Measurements(data),
        options: Options::default(),
    })
    .unwrap();
    let Report::Drives(report) = report.report else {
        panic!("not the six drives")
    };
    let a = report.adequacy.as_ref().unwrap();
    assert_eq!(a.noise_variance, 2.0 * setup.noise().reading_variance);
    assert!((a.noise_ratio - 1.0).abs() < 0.1, "{}", a.noise_ratio);
    assert_eq!(a.verdict(), Some(Verdict::Consistent));
    let u = report.identification.uncertainty.as_ref().unwrap();
    let against_one_reading = (u.residual_variance / setup.noise().reading_variance).sqrt();
    assert!(
        (against_one_reading - 2f64.sqrt()).abs() < 0.15,
        "{against_one_reading}"
    );
}
