//! Synthetic measurements from the forward model, shared by the identification tests and bench.
#![allow(dead_code)] // each user takes its own subset

use nalgebra::{Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::identify::Identification;
use stiffid::internal::observation::Measurement;
use stiffid::{internal::observation::stiffness, Setup};

/// Six spread postures (deg) inside the paper setup's Table 1 bounds.
pub const PAPER_POSTURES_DEG: [[f64; 6]; 6] = [
    [10.0, -20.0, -100.0, 30.0, 40.0, 50.0],
    [-40.0, 10.0, -70.0, -60.0, -30.0, 120.0],
    [60.0, -40.0, -140.0, 90.0, 60.0, -90.0],
    [-70.0, 30.0, -60.0, -150.0, -70.0, 10.0],
    [30.0, -50.0, -160.0, 160.0, 20.0, -150.0],
    [0.0, 0.0, -90.0, 45.0, -45.0, 90.0],
];

/// The guide's cell around the paper setup: floor at z = 0, 50 mm clearance, default radii,
/// tracker at (3000, -2000, 1500) mm.
pub const PAPER_CELL: &str = "
[cell]
floor_z_mm = 0.0
clearance_mm = 50.0
[tracker]
position_mm = [3000.0, -2000.0, 1500.0]
";

/// The paper setup with extra TOML appended (cell tables, constraints).
pub fn paper_with(extra: &str) -> stiffid::Result<Setup> {
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165")?.to_string() + extra;
    stiffid::internal::setup::parse(&text, "cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
}

/// Degrees to radians.
pub fn deg(q: &[f64; 6]) -> Vector6<f64> {
    Vector6::from_iterator(q.iter().map(|v| v.to_radians()))
}

/// Noise-free measurements of every measuring point in each posture, under `wrench(posture)`,
/// with the setup's nominal stiffness.
pub fn synthetic(
    setup: &Setup,
    postures: &[Vector6<f64>],
    wrench: impl Fn(usize, &Vector6<f64>) -> Vector6<f64>,
) -> Vec<Measurement> {
    let mut out = Vec::new();
    for (i, q) in postures.iter().enumerate() {
        let frames = setup.robot().frames(q);
        let w = wrench(i, q);
        let d = stiffness::deflection(setup.arm(), &frames, &w, setup.nominal_stiffness().unwrap());
        for (point, disp) in d.displacements.iter().enumerate() {
            out.push(Measurement {
                posture: i,
                point,
                q: *q,
                e: Default::default(),
                wrench: w,
                displacement: disp.fixed_rows::<3>(0).into_owned(),
            });
        }
    }
    out
}

/// The six postures under the setup's rope-mass load: 24 measurements (72 rows) on the paper setup.
pub fn paper_measurements(setup: &Setup) -> Vec<Measurement> {
    let qs: Vec<_> = PAPER_POSTURES_DEG.iter().map(deg).collect();
    synthetic(setup, &qs, |_, q| {
        setup.rope_wrench(&setup.robot().frames(q))
    })
}

/// The built-in FANUC setup and the real FANUC measurements (examples/data/fanuc-r2000ic-165f),
/// in its base frame.
pub fn fanuc() -> (Setup, Vec<Measurement>) {
    let setup = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    let text = include_str!("../../../../examples/data/fanuc-r2000ic-165f/measurements.csv");
    let mut file = stiffid::internal::io::measurements::parse(text).unwrap();
    file.to_base_frame(&setup).unwrap();
    (setup, file.measurements)
}

/// `data` with independent Gaussian noise of standard deviation `sigma` (m) on every displacement
/// component, drawn in measurement order from `rng`.
pub fn with_noise(data: &[Measurement], sigma: f64, rng: &mut ChaCha8Rng) -> Vec<Measurement> {
    let noise = Normal::new(0.0, sigma).unwrap();
    data.iter()
        .map(|m| Measurement {
            displacement: m.displacement + Vector3::from_fn(|_, _| noise.sample(rng)),
            ..m.clone()
        })
        .collect()
}

/// `setup` on another robot with springs at `springs`, its bounds the robot's joint limits.
pub fn on_robot(setup: &Setup, robot: stiffid::Robot, springs: stiffid::Coordinates) -> Setup {
    let bounds = *robot.limits();
    setup
        .to_builder()
        .with_robot(robot)
        .with_springs(springs)
        .with_bounds(bounds)
        .build()
        .unwrap()
}

/// Noisy measurements of `n` random postures under random wrenches (4 points each on the paper
/// setup), seeded.
pub fn noisy(setup: &Setup, n: usize, seed: u64) -> Vec<Measurement> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (lo, hi) = (setup.robot().limits().lower, setup.robot().limits().upper);
    let postures: Vec<Vector6<f64>> = (0..n)
        .map(|_| Vector6::from_fn(|i, _| lo[i] + rng.random_range(0.1..0.9) * (hi[i] - lo[i])))
        .collect();
    let wrenches: Vec<Vector6<f64>> = (0..n)
        .map(|_| Vector6::from_fn(|i, _| rng.random_range(-1.0..1.0) * [800.0, 150.0][i / 3]))
        .collect();
    let noise = Normal::new(0.0, setup.noise().displacement_sd()).unwrap();
    let mut data = synthetic(setup, &postures, |i, _| wrenches[i]);
    for m in &mut data {
        m.displacement += Vector6::from_fn(|_, _| noise.sample(&mut rng)).fixed_rows::<3>(0);
    }
    data
}

/// Asserts that identification `a` equals `b` to 1e-12 relative (of the largest entry of each
/// quantity): compliance, stiffness, covariance, residuals, RMS, cond, counts, standard errors and
/// intervals.
pub fn assert_close(a: &Identification, b: &Identification) {
    let close = |x: f64, y: f64, scale: f64| (x - y).abs() <= 1e-12 * scale.abs();
    for j in 0..6 {
        assert!(close(a.compliance[j], b.compliance[j], b.compliance.amax()));
        assert!(close(a.stiffness[j], b.stiffness[j], b.stiffness[j]));
    }
    let c = b.unit_covariance.amax();
    assert!((a.unit_covariance - b.unit_covariance).amax() <= 1e-12 * c);
    let r = b.residuals.amax();
    assert!((&a.residuals - &b.residuals).amax() <= 1e-12 * r);
    assert!(close(a.residual_rms, b.residual_rms, b.residual_rms));
    assert!(close(a.cond_psi, b.cond_psi, b.cond_psi));
    assert_eq!((a.rows, a.postures), (b.rows, b.postures));
    let (ua, ub) = (
        a.uncertainty.as_ref().unwrap(),
        b.uncertainty.as_ref().unwrap(),
    );
    assert_eq!(ua.dof, ub.dof);
    for j in 0..6 {
        let se = ub.stiffness_std_error[j];
        assert!(close(ua.stiffness_std_error[j], se, se));
        assert!(close(
            ua.stiffness_ci95[j][1],
            ub.stiffness_ci95[j][1],
            b.stiffness[j]
        ));
    }
}

/// `data` as a measurement CSV (the command's columns, full precision), labels `pose {posture}`.
pub fn measurement_csv(data: &[Measurement]) -> String {
    let mut text = String::from("posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm,dx_mm,dy_mm,dz_mm\n");
    for m in data {
        let d = m.displacement * 1e3;
        let numbers: Vec<String> =
            m.q.map(f64::to_degrees)
                .iter()
                .chain(m.wrench.iter())
                .chain(d.iter())
                .map(|v| format!("{v:e}"))
                .collect();
        text += &format!("pose {},{},{}\n", m.posture, m.point + 1, numbers.join(","));
    }
    text
}

/// A generated program as one text, as the tests' readers of a single file take it: a KRL
/// `.src` with the points its `.dat` declares (`DECL E6POS XP1={..}`, `DECL E6AXIS XP1={..}`)
/// put back into its motions by name (`LIN XP1 C_DIS` becomes `LIN {E6POS: ..} C_DIS`, the
/// literal form KRL reads alone); a program without a `.dat` as it is. Independent of stiffid's
/// readers: the declarations are taken by name from the `.dat`'s lines, and an `XPn` the `.dat`
/// does not declare fails the test.
pub fn inlined(text: &str, data: Option<&str>) -> String {
    let Some(data) = data else {
        return text.to_string();
    };
    let points: std::collections::HashMap<&str, String> = data
        .lines()
        .filter_map(|l| l.strip_prefix("DECL "))
        .filter_map(|l| {
            let (kind, rest) = l.split_once(' ')?;
            let (name, value) = rest.split_once('=')?;
            let members = value.strip_prefix('{')?.strip_suffix('}')?;
            Some(match kind {
                "E6POS" => (name, format!("{{E6POS: {members}}}")),
                _ => (name, format!("{{{members}}}")),
            })
        })
        .collect();
    let mut out = String::with_capacity(text.len() + data.len());
    for line in text.split_inclusive('\n') {
        let motion = ["PTP ", "LIN ", "CIRC "]
            .iter()
            .find(|k| line.starts_with(*k) && line[k.len()..].starts_with("XP"));
        let Some(keyword) = motion else {
            out += line;
            continue;
        };
        out += keyword;
        let mut rest = &line[keyword.len()..];
        let mut first = true;
        while let Some(tail) = rest.strip_prefix("XP") {
            let digits = tail
                .find(|c: char| !c.is_ascii_digit())
                .unwrap_or(tail.len());
            let name = &rest[..2 + digits];
            let value = points
                .get(name)
                .unwrap_or_else(|| panic!("{name} not in the .dat"));
            if !first {
                out += ",";
            }
            out += value;
            first = false;
            rest = &tail[digits..];
            rest = rest.strip_prefix(", ").unwrap_or(rest);
        }
        out += rest;
    }
    out
}

/// A compensated program's text as one file ([`inlined`]: a KRL program's `.dat` points put
/// back into its `.src`).
pub fn program_text(p: stiffid::app::compensate::ProgramReport) -> String {
    inlined(&p.text, p.data.as_deref())
}

/// The milling example's KRL program as one text: `examples/milling/pocket.src` with the points
/// of its `pocket.dat` put back into its motions ([`inlined`]), for tests that read or edit one
/// file.
pub fn pocket_krl() -> &'static str {
    static TEXT: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
        inlined(
            include_str!("../../../../examples/milling/pocket.src"),
            Some(include_str!("../../../../examples/milling/pocket.dat")),
        )
    });
    &TEXT
}

/// The milling example's stiffness file (the FANUC's real data) as the compliance of `setup`'s
/// model.
pub fn milling_compliance(setup: &Setup) -> stiffid::internal::machining::compensate::Compliance {
    stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(setup.model())
    .unwrap()
}

/// The milling example's process file (aluminium).
pub fn milling_process() -> stiffid::internal::machining::process::Process {
    stiffid::internal::machining::process::file::parse(
        include_str!("../../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap()
}

/// Whether a search stopped where a step no longer improves (converged or at the step
/// tolerance).
pub fn converged(t: stiffid::internal::design::Termination) -> bool {
    matches!(
        t,
        stiffid::internal::design::Termination::Converged
            | stiffid::internal::design::Termination::StepTolerance
    )
}
