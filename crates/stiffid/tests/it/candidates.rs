//! The candidates of the model comparison (crate::identify::compare::pool): springs declared in
//! the setup as candidates, the wider default pool and what it drops, and a declared candidate that
//! is the truth found by the comparison.

use nalgebra::{DVector, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::design::random_group;
use stiffid::internal::identify::compare::{compare, default_pool, pool_by_name};
use stiffid::internal::identify::svd::fit;
use stiffid::internal::observation::{posture_block, Measurement, Observations};
use stiffid::internal::setup::Setup;

/// A bending spring of the forearm about the z axis of link 3's frame through a point 600 mm
/// along its x axis (the paper's COMAU cell; as a new user would declare an elbow spring).
pub const ELBOW: &str = r#"
[[model.spring]]
name = "elbow_z"
kind = "rotation"
link = 3
axis = [0, 0, 1]
point_mm = [600, 0, 0]
nominal_stiffness_nm_per_rad = 4e6
"#;

/// The paper's setup with `extra` appended to its TOML.
pub fn paper_with(extra: &str) -> Setup {
    let text = format!(
        "{}\n{extra}",
        stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap()
    );
    stiffid::internal::setup::parse(&text, "test setup", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap()
}

/// Measurements of `postures` under the rope load with compliance `h` of `truth`'s model, plus
/// Gaussian noise of standard deviation `sigma` (m).
pub fn measure(
    truth: &Setup,
    postures: &[Vector6<f64>],
    h: &DVector<f64>,
    sigma: f64,
    seed: u64,
) -> Vec<Measurement> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 1.0).unwrap();
    let mut out = Vec::new();
    for (posture, q) in postures.iter().enumerate() {
        let frames = truth.robot().frames(q);
        let wrench = truth.rope_wrench(&frames);
        let d = posture_block(truth.arm(), &frames, &wrench) * h;
        for point in 0..truth.tool().measuring_points.len() {
            let noise = Vector3::from_fn(|_, _| sigma * normal.sample(&mut rng));
            out.push(Measurement {
                posture,
                point,
                q: *q,
                e: Default::default(),
                wrench,
                displacement: d.fixed_rows::<3>(3 * point).into_owned() + noise,
            });
        }
    }
    out
}

/// `candidate = true` keeps a spring out of the model and puts it in the pool, first; the truth
/// (drives plus that spring) measured noise-free gives its compliance back to 1e-9 when the
/// setup's model is fitted with it, and the comparison recommends it.
#[test]
fn a_declared_candidate_is_in_the_pool_and_recovered_noise_free() {
    let truth = paper_with(ELBOW);
    assert_eq!(truth.model().springs()[0].name, "elbow_z");
    let declared = paper_with(&ELBOW.replace("rotation\"", "rotation\"\ncandidate = true"));
    assert!(declared.model().is_drives_only());
    assert_eq!(declared.candidate_springs().len(), 1);
    let pool = default_pool(&declared);
    assert_eq!(pool.candidates[0].name, "elbow_z");
    let h = truth.model_nominal_compliance().unwrap();
    let postures = random_group(&truth, 14, 3);
    let data = measure(&truth, &postures, &h, 0.0, 0);
    let obs = Observations::from_measurements(truth.arm(), &data).unwrap();
    let f = fit(&obs, &truth.model().parameters()).unwrap();
    for j in 0..7 {
        assert!(
            (f.compliance[j] / h[j] - 1.0).abs() < 1e-9,
            "{j}: {} vs {}",
            f.compliance[j],
            h[j]
        );
    }
    let c = compare(&declared, &data, &pool.candidates, false).unwrap();
    // The first step adds the declared spring (the rest of the path lowers a held-out error
    // of rounding size).
    assert_eq!(c.models[1].added.as_deref(), Some("elbow_z"));
    assert!(c.models[1].held_out_rms_delta_b.unwrap() < 1e-12);
    let rec = &c.models[c.recommended];
    assert!(
        rec.springs.iter().any(|s| s == "elbow_z"),
        "{:?}",
        rec.springs
    );
    let j = c
        .recommended_fit
        .parameters
        .iter()
        .position(|p| p.name == "elbow_z")
        .unwrap();
    let got = c.recommended_fit.compliance[j];
    assert!((got / h[6] - 1.0).abs() < 1e-9, "{got} vs {}", h[6]);
}

/// On seeded noisy simulations (the setup's tracker noise) of the drives plus the declared elbow
/// spring, the recommended model of the default pool (every family and the declared candidate)
/// holds the declared spring every time.
#[test]
fn the_recommended_model_holds_the_true_declared_candidate() {
    let truth = paper_with(ELBOW);
    let declared = paper_with(&ELBOW.replace("rotation\"", "rotation\"\ncandidate = true"));
    let h = truth.model_nominal_compliance().unwrap();
    let pool = default_pool(&declared);
    assert!(pool.candidates.len() > 20, "{}", pool.candidates.len());
    let sigma = truth.noise().displacement_sd();
    for seed in 0..5 {
        let postures = random_group(&truth, 15, 10 + seed);
        let data = measure(&truth, &postures, &h, sigma, seed);
        let c = compare(&declared, &data, &pool.candidates, false).unwrap();
        let rec = &c.models[c.recommended];
        assert!(
            rec.springs.iter().any(|s| s == "elbow_z"),
            "seed {seed}: {:?}",
            rec.springs
        );
    }
}

/// On the FANUC robot (modified DH) the pool drops the axes that are a joint's own, naming the
/// joint: `tilt3_z` (joint 3), `tilt4_y` (joint 5), `base_rz` (joint 1); asking for one of them
/// alone says why it is not a candidate.
#[test]
fn axes_along_a_joints_own_are_dropped_with_the_reason() {
    let fanuc = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    let pool = default_pool(&fanuc);
    let reason = |name: &str| {
        pool.dropped
            .iter()
            .find(|d| d.name == name)
            .map(|d| d.reason.clone())
            .unwrap_or_else(|| panic!("{name} not dropped: {:?}", pool.dropped))
    };
    assert!(
        reason("tilt3_z").contains("joint 3's own"),
        "{}",
        reason("tilt3_z")
    );
    assert!(
        reason("tilt4_y").contains("joint 5's own"),
        "{}",
        reason("tilt4_y")
    );
    assert!(
        reason("base_rz").contains("joint 1's own"),
        "{}",
        reason("base_rz")
    );
    for kept in [
        "tilt3_x", "tilt3_y", "bend2_y", "bend3_z", "tool_y", "base_x",
    ] {
        assert!(pool.candidates.iter().any(|s| s.name == kept), "{kept}");
    }
    assert!(pool
        .candidates
        .iter()
        .all(|s| pool.dropped.iter().all(|d| d.name != s.name)));
    let err = pool_by_name(&fanuc, &["tilt3_z".to_string()])
        .unwrap_err()
        .to_string();
    assert!(err.contains("joint 3's own"), "{err}");
    let err = pool_by_name(&fanuc, &["tilt9_x".to_string()])
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("'tilt9_x' is not a candidate") && err.contains("bend2_y"),
        "{err}"
    );
    let bend = pool_by_name(&fanuc, &["bend".to_string(), "tool_y".to_string()]).unwrap();
    assert!(bend
        .candidates
        .iter()
        .all(|s| s.name.starts_with("bend") || s.name == "tool_y"));
}

/// A fragment may not declare candidates (they belong in the setup file), and a candidate may not
/// share a name with the model's springs.
#[test]
fn candidates_are_refused_where_they_do_not_belong() {
    let fanuc = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    let fragment = ELBOW.replace("rotation\"", "rotation\"\ncandidate = true");
    let err = stiffid::internal::model::parse_fragment(&fragment, "model.toml", fanuc.robot())
        .unwrap_err()
        .to_string();
    assert!(err.contains("model.spring[1].candidate"), "{err}");
    let text = format!(
        "{}\n{ELBOW}\n{}",
        stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap(),
        fragment
    );
    let err = stiffid::internal::setup::parse(&text, "s.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("model.spring[2].name") && err.contains("unique"),
        "{err}"
    );
}

/// A lost motion of joint 3 (`lost3`, 200 urad, smoothed over 10 Nm) on top of the drives,
/// measured noise-free at three load levels in each posture (load steps of 30%, 65% and 100% of
/// the rope load): the fit of that model gives every parameter back to 1e-9, and the comparison
/// over the `lost` and `load` candidates adds `lost3` first and says the data separate them.
#[test]
fn a_lost_motion_is_recovered_from_load_steps() {
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let pool = pool_by_name(&paper, &["lost".to_string(), "load".to_string()]).unwrap();
    assert_eq!(pool.candidates.len(), 12);
    let lost3 = pool
        .candidates
        .iter()
        .find(|s| s.name == "lost3")
        .unwrap()
        .clone();
    let truth = paper
        .to_builder()
        .with_virtual_springs(vec![lost3])
        .build()
        .unwrap();
    assert_eq!(truth.model().parameters()[6].unit.symbol(), "urad");
    let mut h = DVector::zeros(7);
    h.rows_mut(0, 6)
        .copy_from(&paper.model_nominal_compliance().unwrap());
    h[6] = 200e-6;
    let mut data = Vec::new();
    for (posture, q) in random_group(&paper, 10, 5).iter().enumerate() {
        let frames = truth.robot().frames(q);
        for level in [0.3, 0.65, 1.0] {
            let wrench = truth.rope_wrench(&frames) * level;
            let d = posture_block(truth.arm(), &frames, &wrench) * &h;
            for point in 0..truth.tool().measuring_points.len() {
                data.push(Measurement {
                    posture,
                    point,
                    q: *q,
                    e: Default::default(),
                    wrench,
                    displacement: d.fixed_rows::<3>(3 * point).into_owned(),
                });
            }
        }
    }
    let obs = Observations::from_measurements(truth.arm(), &data).unwrap();
    let f = fit(&obs, &truth.model().parameters()).unwrap();
    for j in 0..7 {
        assert!(
            (f.compliance[j] / h[j] - 1.0).abs() < 1e-9,
            "{j}: {} vs {}",
            f.compliance[j],
            h[j]
        );
    }
    let c = compare(&paper, &data, &pool.candidates, false).unwrap();
    assert_eq!(c.models[1].added.as_deref(), Some("lost3"));
    assert_eq!(c.load_levels, 3);
    assert!(c.nonlinear_separation().unwrap().contains("3 load levels"));
}

/// A declared candidate named like a family's candidate is refused naming it (it used to
/// replace the family's without a word); every family candidate of the default pool, kept or
/// dropped, has a name the check knows, and a name of the user's own passes.
#[test]
fn a_declared_candidate_named_like_a_family_is_refused() {
    let base = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap();
    // The setup with `ELBOW` declared as a candidate named `name`: refused naming it, or read.
    let declared = |name: &str| {
        let named =
            (ELBOW.replace("elbow_z", name)).replace("rotation\"", "rotation\"\ncandidate = true");
        let text = format!("{base}\n{named}");
        stiffid::internal::setup::parse(&text, "test setup", |r, _| {
            stiffid::internal::robot::presets::get(r)
        })
        .map(|_| ())
        .map_err(|e| e.to_string())
    };
    let refused = |name: &str| match declared(name) {
        Ok(()) => panic!("{name}: not refused"),
        Err(e) => assert!(
            e.contains(&format!(
                "\"{name}\": a declared candidate named like a built-in"
            )),
            "{e}"
        ),
    };
    refused("tilt3_z");
    let declared_setup = paper_with(&ELBOW.replace("rotation\"", "rotation\"\ncandidate = true"));
    let pool = default_pool(&declared_setup);
    assert_eq!(pool.candidates[0].name, "elbow_z");
    let families = pool.candidates[1..].iter().map(|c| &c.name);
    for name in families.chain(pool.dropped.iter().map(|d| &d.name)) {
        refused(name);
    }
    for own in [
        "elbow_z", "tilt7_z", "bend6_x", "lost0", "tool_w", "tilt3_z2",
    ] {
        assert_eq!(declared(own), Ok(()), "{own}");
    }
}
