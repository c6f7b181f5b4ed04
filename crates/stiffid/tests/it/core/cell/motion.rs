//! The exact margin gradients against central differences, at random feasible postures of every
//! robot preset in a cell with every check.

use nalgebra::Vector6;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid_core::cell::{CheckKind, Checker};
use stiffid_core::robot::presets;
use stiffid_core::setup::Setup;

/// The paper setup on `robot`, within its joint limits, in a cell with a floor, a table, a
/// tracker with an incidence limit and both `[constraints]`.
fn cell(robot: &str) -> Setup {
    let text = stiffid_core::setup::builtin_text("zhang2021-comau-nj165").unwrap().to_string()
        + "\n[cell]\nfloor_z_mm = -100.0\nclearance_mm = 50.0\n\
           [[cell.obstacle]]\nname = \"table\"\nmin_mm = [1200.0, -2000.0, -100.0]\nmax_mm = [2200.0, -600.0, 700.0]\n\
           [tracker]\nposition_mm = [3000.0, -2000.0, 1500.0]\nmax_incidence_deg = 70.0\n\
           [constraints]\nloading_point_min_z_mm = 200.0\nanchor_below_loading_point = true\n";
    let setup = stiffid_core::setup::parse(&text, "cell.toml", |r, _| presets::get(r)).unwrap();
    let robot = presets::get(robot).unwrap();
    let geometry = stiffid_core::setup::default_geometry(&robot, setup.tool());
    let builder = setup.to_builder().with_bounds(*robot.limits());
    builder
        .with_geometry(geometry)
        .with_robot(robot)
        .build()
        .unwrap()
}

/// Postures drawn uniformly within the bounds that pass every check.
fn feasible(setup: &Setup, checker: &Checker, count: usize) -> Vec<Vector6<f64>> {
    let b = setup.bounds();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut out = Vec::new();
    for _ in 0..200_000 {
        let q = Vector6::from_fn(|a, _| rng.random_range(b.lower[a]..=b.upper[a]));
        if checker.violation(&q) == 0.0 {
            out.push(q);
            if out.len() == count {
                break;
            }
        }
    }
    out
}

#[test]
fn margin_gradients_match_central_differences() {
    for robot in presets::names() {
        let (compared, kinds) = compare(&cell(robot), robot, 8, 0.0);
        assert!(compared > 1000, "{robot}: {compared}");
        assert_eq!(kinds.len(), CheckKind::ALL.len() - 1, "{robot}: {kinds:?}");
    }
}

use crate::bodies::mesh_robot;

/// The mesh robot's setup ([`mesh_robot::setup_toml`]) read from memory, its hulls as bodies.
pub(crate) fn mesh_setup() -> Setup {
    use std::path::{Path, PathBuf};
    let files: std::collections::HashMap<PathBuf, Vec<u8>> = mesh_robot::files(48)
        .into_iter()
        .map(|(p, b)| (Path::new("pkg").join(p), b))
        .collect();
    let text = |p: &Path| {
        let b = files.get(p)?;
        Some(Ok::<_, stiffid_core::Error>(
            String::from_utf8(b.clone()).unwrap(),
        ))
    };
    let bytes = |p: &Path| files.get(p).cloned().map(Ok);
    let meshes = stiffid_core::setup::reference::Meshes {
        read: &bytes,
        package_paths: &[],
    };
    let toml = mesh_robot::setup_toml() + "[constraints]\nloading_point_min_z_mm = 200.0\n";
    let toml = toml.replace("[tracker]\n", "[tracker]\nmax_incidence_deg = 70.0\n");
    stiffid_core::setup::reference::setup_text_with_meshes(
        &toml,
        "pkg/cell.toml",
        Path::new("pkg"),
        text,
        &meshes,
    )
    .unwrap()
}

/// The same with the robot's collision hulls (convex polyhedra, GJK's witness points).
#[test]
fn hull_margin_gradients_match_central_differences() {
    let setup = mesh_setup();
    assert!(setup.shapes().is_some());
    let (compared, kinds) = compare(&setup, "mesh robot", 8, 0.0);
    assert!(compared > 500, "{compared}");
    assert!(kinds.contains(&CheckKind::SelfCollision), "{kinds:?}");
    assert!(kinds.contains(&CheckKind::Floor), "{kinds:?}");
}

/// A checker that keeps 10 mm: every margin is the plain one less 10 mm (less `0.01 / L` rad
/// for the incidence, `L` the line of sight's length; the tool against a line too: its exempt
/// part does not grow with the margin), and its gradients are still exact.
#[test]
fn kept_margins_are_the_plain_ones_less_the_margin_with_exact_gradients() {
    // A margin random postures within the robot's limits keep to the tool's lines of sight.
    const KEEP: f64 = 0.01;
    let setup = cell(presets::names().next().unwrap());
    let (plain, kept) = (Checker::new(&setup), Checker::new(&setup).keeping(KEEP));
    let tracker = setup.tracker().unwrap().position;
    let mut seen = std::collections::BTreeSet::new();
    for q in feasible(&setup, &plain, 6) {
        let frames = setup.robot().frames(&q);
        for (a, b) in plain.margins(&q).iter().zip(kept.margins(&q)) {
            let less = match (a.kind, a.between.0) {
                (CheckKind::Bounds, _) => 0.0,
                (CheckKind::Incidence, stiffid_core::cell::Thing::MeasuringPoint(i)) => {
                    let p = frames.point(&setup.tool().measuring_points[i]);
                    KEEP / (tracker - p).norm()
                }
                _ => KEEP,
            };
            // A pair within FAR_MARGIN of its requirement is exact in both (never broad phase),
            // as a line against an obstacle always is.
            let line = matches!(a.kind, CheckKind::Rope | CheckKind::LineOfSight);
            let obstacle = matches!(a.between.1, stiffid_core::cell::Thing::Obstacle(_));
            let exact = a.kind.is_angle()
                || (line && obstacle)
                || a.margin < 0.1
                || matches!(
                    a.kind,
                    CheckKind::LoadingPointHeight | CheckKind::AnchorBelow
                );
            if a.margin.is_finite() && exact {
                assert!((a.margin - b.margin - less).abs() < 1e-12, "{a:?} {b:?}");
                seen.insert(a.kind);
            }
        }
    }
    for kind in [
        CheckKind::Rope,
        CheckKind::LineOfSight,
        CheckKind::Incidence,
        CheckKind::LoadingPointHeight,
        CheckKind::AnchorBelow,
    ] {
        assert!(seen.contains(&kind), "{kind}: {seen:?}");
    }
    let (compared, kinds) = compare(&setup, "kept", 6, KEEP);
    assert!(compared > 500, "{compared}");
    assert!(kinds.contains(&CheckKind::Incidence), "{kinds:?}");
}

/// Compares every margin's exact gradient with central differences at `count` feasible postures
/// of `setup` (for a checker keeping `keep`, m): how many derivatives were compared and of which
/// checks.
fn compare(
    setup: &Setup,
    robot: &str,
    count: usize,
    keep: f64,
) -> (usize, std::collections::BTreeSet<CheckKind>) {
    let h = 1e-5;
    let checker = Checker::new(setup).keeping(keep);
    let postures = feasible(setup, &checker, count);
    assert_eq!(postures.len(), count, "{robot}");
    let (mut compared, mut kinds) = (0, std::collections::BTreeSet::new());
    for q in &postures {
        let (margins, gradients) = checker.margins_and_gradients(q);
        let mut probes = [[0.0; 2]; 6].map(|_| Vec::new());
        for a in 0..6 {
            for (side, s) in [(0, h), (1, -h)] {
                let mut p = *q;
                p[a] += s;
                probes[a].push((side, checker.margins(&p)));
            }
        }
        for (k, m) in margins.iter().enumerate() {
            let g = gradients.gradient(k);
            if !m.margin.is_finite() || m.kind == CheckKind::Bounds {
                continue;
            }
            for a in 0..6 {
                let (plus, minus) = (probes[a][0].1[k].margin, probes[a][1].1[k].margin);
                let (forward, backward) = ((plus - m.margin) / h, (m.margin - minus) / h);
                // A tie (two closest pairs of points) is a kink: the one-sided slopes differ.
                if (forward - backward).abs() > 1e-4 * (1.0 + forward.abs()) {
                    continue;
                }
                let central = (plus - minus) / (2.0 * h);
                assert!(
                    (g[a] - central).abs() <= 1e-5 * (1.0 + central.abs()),
                    "{robot}, {} {:?}, axis {}: exact {} vs central {central} at {q:?}",
                    m.kind,
                    m.between,
                    a + 1,
                    g[a]
                );
                compared += 1;
            }
            kinds.insert(m.kind);
        }
    }
    (compared, kinds)
}
