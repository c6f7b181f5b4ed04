//! The virtual springs' columns against finite differences of the virtual joint, and the
//! `[model]` table of a setup file.

use nalgebra::{Rotation3, Vector3, Vector6};
use stiffid_core::model::*;
use stiffid_core::observation::posture_block;
use stiffid_core::setup::Setup;

/// The paper's setup with a spring of every kind and link: the elbow tilt family, a rotation
/// about an off-origin axis in link 1, the tool translations and the base mount.
fn extended() -> Setup {
    let text = stiffid_core::setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .to_string()
        + r#"
[[model.spring]]
name = "upper_arm"
kind = "rotation"
link = 1
axis = [0.3, -1, 0.2]
point_mm = [100, -50, 400]
nominal_stiffness_nm_per_rad = 5e6

[[model.family]]
family = "tilt"
links = [3]
nominal_stiffness_nm_per_rad = 4e6

[[model.family]]
family = "tool"
nominal_stiffness_n_per_mm = 2e4

[[model.family]]
family = "base"
nominal_stiffness_nm_per_rad = 2e7
nominal_stiffness_n_per_mm = 1e5
"#;
    stiffid_core::setup::parse(&text, "extended.toml", |r, _| {
        stiffid_core::robot::presets::get(r)
    })
    .unwrap()
}

/// The position of a base-frame point after the virtual joint moves by `e` (rad or m).
fn moved(s: &Placed, p: &Vector3<f64>, e: f64) -> Vector3<f64> {
    match s.kind {
        Kind::Rotation => {
            let r = Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(s.u), e);
            s.o + r * (p - s.o)
        }
        Kind::Translation => p + s.u * e,
    }
}

/// Column `6 + s` of a posture's block is `c`-free `J_m,s (J_f,s^T W)`: the central difference of
/// the measuring point's position when the virtual joint turns or slides (an independent rotation
/// matrix), times the generalised load, itself the central difference of the virtual work of the
/// wrench at the loading point.
#[test]
fn spring_columns_are_finite_differences_of_the_virtual_joint() {
    let setup = extended();
    assert_eq!(setup.model().len(), 6 + 1 + 2 + 3 + 6);
    let e = 1e-6;
    for q in stiffid_design::random_group(&setup, 4, 3) {
        let frames = setup.robot().frames(&q);
        let wrench = setup.rope_wrench(&frames) + Vector6::new(0.0, 0.0, 0.0, 30.0, -20.0, 10.0);
        let block = posture_block(setup.arm(), &frames, &wrench);
        assert_eq!(block.ncols(), setup.model().len());
        let pf = frames.point(&setup.tool().loading_point);
        for (s, spring) in setup.model().springs().iter().enumerate() {
            let placed = spring.placed(&frames);
            let dpf = (moved(&placed, &pf, e) - moved(&placed, &pf, -e)) / (2.0 * e);
            let rotation = match placed.kind {
                Kind::Rotation => placed.u,
                Kind::Translation => Vector3::zeros(),
            };
            let load =
                wrench.fixed_rows::<3>(0).dot(&dpf) + wrench.fixed_rows::<3>(3).dot(&rotation);
            for (k, point) in setup.tool().measuring_points.iter().enumerate() {
                let p = frames.point(point);
                let dp = (moved(&placed, &p, e) - moved(&placed, &p, -e)) / (2.0 * e) * load;
                let column = block.fixed_view::<3, 1>(3 * k, 6 + s);
                let scale = column.norm().max(1e-3);
                assert!(
                    (column - dp).norm() < 1e-7 * scale,
                    "{}: {column} vs {dp}",
                    spring.name
                );
            }
        }
        // The drive columns are those of the drives-only model.
        let drives = posture_block(
            stiffid_core::setup::builtin("zhang2021-comau-nj165")
                .unwrap()
                .arm(),
            &frames,
            &wrench,
        );
        assert_eq!(block.columns(0, 6), drives);
    }
}

/// Families give the documented names, units, links and axes; the flange's axes for `tool`.
#[test]
fn families_and_parameters() {
    let setup = extended();
    let names: Vec<String> = setup
        .model()
        .parameters()
        .into_iter()
        .map(|p| p.name)
        .collect();
    assert_eq!(
        names,
        [
            "k1",
            "k2",
            "k3",
            "k4",
            "k5",
            "k6",
            "upper_arm",
            "tilt3_x",
            "tilt3_y",
            "tool_x",
            "tool_y",
            "tool_z",
            "base_x",
            "base_y",
            "base_z",
            "base_rx",
            "base_ry",
            "base_rz"
        ]
    );
    let springs = setup.model().springs();
    assert_eq!(springs[1].link, 3);
    assert_eq!(springs[1].axis.into_inner(), Vector3::x());
    assert_eq!(springs[3].unit(), Unit::NPerMm);
    assert_eq!(springs[3].nominal_stiffness, Some(2e7));
    // tool_x is along the flange's x axis at every posture.
    let q = Vector6::new(0.3, -0.2, -1.2, 0.5, 0.7, -0.4);
    let frames = setup.robot().frames(&q);
    let u = springs[3].placed(&frames).u;
    let x = frames.flange.rotation * Vector3::x();
    assert!((u - x).norm() < 1e-14);
    let h = setup.model_nominal_compliance().unwrap();
    assert_eq!(h.len(), 18);
    assert_eq!(h[7], 1.0 / 4e6);
    // The fragment of a model reads back as the same springs.
    let again = stiffid_core::setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .to_string()
        + &fragment(springs);
    let again = stiffid_core::setup::parse(&again, "again.toml", |r, _| {
        stiffid_core::robot::presets::get(r)
    })
    .unwrap();
    assert_eq!(again.model(), setup.model());
}

/// Bad `[model]` entries are errors naming the field.
#[test]
fn bad_springs_name_the_field() {
    let base = stiffid_core::setup::builtin_text("zhang2021-comau-nj165").unwrap();
    let cases = [
        ("[[model.spring]]\nname = \"a\"\nkind = \"rotation\"\nlink = 7\naxis = [1, 0, 0]\n", "model.spring[1].link"),
        ("[[model.spring]]\nname = \"a\"\nkind = \"rotation\"\nlink = 2\naxis = [0, 0, 0]\n", "model.spring[1].axis"),
        ("[[model.spring]]\nname = \"k3\"\nkind = \"rotation\"\nlink = 2\naxis = [0, 0, 1]\n", "model.spring[1].name"),
        ("[[model.spring]]\nname = \"a b\"\nkind = \"rotation\"\nlink = 2\naxis = [0, 0, 1]\n", "model.spring[1].name"),
        ("[[model.spring]]\nname = \"t\"\nkind = \"translation\"\nlink = 2\naxis = [0, 0, 1]\npoint_mm = [0, 0, 0]\n", "model.spring[1].point_mm"),
        ("[[model.spring]]\nname = \"t\"\nkind = \"translation\"\nlink = 2\naxis = [0, 0, 1]\nnominal_stiffness_nm_per_rad = 1e5\n", "model.spring[1].nominal_stiffness_nm_per_rad"),
        ("[[model.spring]]\nname = \"t\"\nkind = \"translation\"\nlink = 2\naxis = [0, 0, 1]\nnominal_stiffness_n_per_mm = 1e30\n", "model.spring[1].nominal_stiffness_n_per_mm"),
        ("[[model.spring]]\nname = \"r\"\nkind = \"rotation\"\nlink = 2\naxis = [0, 0, 1]\npoint_mm = [1e9, 0, 0]\n", "model.spring[1].point_mm"),
        ("[[model.family]]\nfamily = \"tilt\"\nlinks = [3, 3]\n", "model.family[1].links"),
        ("[[model.family]]\nfamily = \"tilt\"\n", "model.family[1].links"),
        ("[[model.family]]\nfamily = \"tool\"\nlinks = [6]\n", "model.family[1].links"),
        ("[[model.family]]\nfamily = \"bend\"\n", "model.family[1].family"),
        ("[[model.family]]\nfamily = \"tilt\"\nlinks = [2]\n[[model.family]]\nfamily = \"tilt\"\nlinks = [2]\n", "model.spring[3].name"),
    ];
    for (fragment, field) in cases {
        let text = format!("{base}\n{fragment}");
        match stiffid_core::setup::parse(&text, "s.toml", |r, _| {
            stiffid_core::robot::presets::get(r)
        }) {
            Err(stiffid_core::Error::InvalidField { field: f, message }) => {
                assert!(
                    f.starts_with(&format!("s.toml: {field}")),
                    "{fragment}: {f}: {message}"
                )
            }
            other => panic!("{fragment}: {other:?}"),
        }
    }
}
