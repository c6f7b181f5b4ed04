use crate::model::*;
use nalgebra::Vector3;

/// A rotational spring on link 3 with `law` and the nominal stiffness `k` (Nm/rad).
fn spring(law: Law, k: f64) -> Spring {
    Spring {
        name: "bend".into(),
        kind: Kind::Rotation,
        link: 3,
        axis: Vector3::y_axis(),
        point: Vector3::zeros(),
        nominal_stiffness: Some(k),
        law,
    }
}

#[test]
fn a_nonlinear_springs_nominal_stiffness_is_checked_as_the_user_gave_it() {
    for law in [
        Law::Linear,
        Law::LostMotion { smoothing: 10.0 },
        Law::LoadDependent,
    ] {
        assert!(check_springs(&[spring(law, 4e6)]).is_ok(), "{law:?}");
        let e = check_springs(&[spring(law, 4e10)]).unwrap_err().to_string();
        assert!(
            e.starts_with("model.spring[1].nominal_stiffness_nm_per_rad: 4e10 is outside"),
            "{law:?}: {e}"
        );
    }
}
