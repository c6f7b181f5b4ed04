//! The controllers' speed readers (`crate::program::speed` and each language's `speed`).

use crate::program::inform::speed::speed as inform;
use crate::program::krl::speed::Krl;
use crate::program::ls::speed::speed as ls;
use crate::program::rapid::speed::{speed as rapid, RapidSpeeds};
use crate::program::speed::Speed;

fn mm_s(s: Speed) -> f64 {
    match s {
        Speed::Path(v) => v * 1e3,
        other => panic!("expected a path speed, got {other:?}"),
    }
}

#[test]
fn krl_speeds_in_force_and_per_motion() {
    let mut k = Krl::new();
    assert!(matches!(k.motion(1, "LIN", "").unwrap(), Speed::Unread(_)));
    assert_eq!(k.motion(1, "PTP", "").unwrap(), Speed::Joint);
    assert!(k.set(2, " $vel.cp = 0.25 ").unwrap());
    assert!((mm_s(k.motion(3, "LIN", " C_DIS").unwrap()) - 250.0).abs() < 1e-9);
    assert!(k.set(4, "BAS (#CP_PARAMS, 0.5)").unwrap());
    assert!((mm_s(k.motion(5, "SLIN", "").unwrap()) - 500.0).abs() < 1e-9);
    let with = k.motion(6, "SLIN", " WITH $VEL = SVEL_CP(0.02, , LCPDAT1)");
    assert!((mm_s(with.unwrap()) - 20.0).abs() < 1e-9);
    assert!((mm_s(k.motion(6, "LIN", " WITH $VEL.CP = 0.1").unwrap()) - 100.0).abs() < 1e-9);
    assert!(!k.set(7, "$VEL.ORI1 = 200").unwrap());
    assert!(k.set(8, "$VEL.CP = $VEL_MA.CP * 0.5").unwrap());
    assert!(matches!(k.motion(9, "LIN", "").unwrap(), Speed::Unread(w) if w.contains("line 8")));
    // The old inline forms' BAS(#CP_DAT) takes LDAT_ACT's speed, which is not read.
    assert!(k.set(9, "BAS (#CP_DAT)").unwrap());
    assert!(matches!(k.motion(10, "LIN", "").unwrap(), Speed::Unread(w) if w.contains("line 9")));
    for bad in [
        "$VEL.CP = -1",
        "$VEL.CP = 0",
        "$VEL.CP = 11",
        "BAS(#CP_PARAMS, 0)",
    ] {
        let e = Krl::new().set(10, bad).unwrap_err().to_string();
        assert!(
            e.contains("line 10") && e.contains("(0, 10000] mm/s"),
            "{bad}: {e}"
        );
    }
}

#[test]
fn rapid_speeds_predefined_declared_and_switches() {
    let mut declared = RapidSpeeds::new();
    declared.insert("vcut".into(), Ok((25.0, 3)));
    declared.insert("vrun".into(), Err("vrun is assigned on line 9".into()));
    let s = |a: &str| rapid(20, "movel", Some(a), &declared).unwrap();
    assert!((mm_s(s(" v100")) - 100.0).abs() < 1e-12);
    assert!((mm_s(s(" V7000")) - 7000.0).abs() < 1e-9);
    assert!((mm_s(s(" vcut")) - 25.0).abs() < 1e-12);
    assert!((mm_s(s(" [5,500,5000,1000]")) - 5.0).abs() < 1e-12);
    assert!(matches!(s(" [5,500]"), Speed::Unread(_)));
    assert!((mm_s(s(" v100\\V:=120")) - 120.0).abs() < 1e-12);
    assert_eq!(s(" v100 \\T:=2.5"), Speed::Duration(2.5));
    assert!(matches!(s(" vrun"), Speed::Unread(w) if w.contains("line 9")));
    assert!(matches!(s(" vmax"), Speed::Unread(_)));
    assert!(matches!(s(" v123"), Speed::Unread(w) if w.contains("v5 to v7000")));
    assert!(matches!(s(" v100\\V:=speed"), Speed::Unread(_)));
    assert_eq!(rapid(1, "moveabsj", None, &declared).unwrap(), Speed::Joint);
    let e = rapid(21, "movel", Some("v100\\V:=-3"), &declared).unwrap_err();
    assert!(e.to_string().contains("line 21"), "{e}");
    let e = rapid(22, "movel", Some("v100\\T:=0"), &declared).unwrap_err();
    assert!(e.to_string().contains("(0, 3600] s"), "{e}");
}

#[test]
fn ls_speed_units() {
    let s = |w: &str| ls(3, "L", w).unwrap();
    assert!((mm_s(s("100mm/sec")) - 100.0).abs() < 1e-12);
    assert!((mm_s(s("600cm/min")) - 100.0).abs() < 1e-9);
    assert!((mm_s(s("60inch/min")) - 25.4).abs() < 1e-9);
    assert_eq!(s("2sec"), Speed::Duration(2.0));
    assert_eq!(s("500msec"), Speed::Duration(0.5));
    assert!(matches!(s("R[1]mm/sec"), Speed::Unread(w) if w.contains("register")));
    assert!(matches!(s("90deg/sec"), Speed::Unread(_)));
    assert!(matches!(s("max_speed"), Speed::Unread(_)));
    assert_eq!(ls(3, "J", "100%").unwrap(), Speed::Joint);
    assert!(ls(4, "L", "0mm/sec")
        .unwrap_err()
        .to_string()
        .contains("line 4"));
}

#[test]
fn inform_speed_tags() {
    let s = |t: &[&str]| inform(5, "MOVL", t).unwrap();
    assert!((mm_s(s(&["V=83.3", "PL=0"])) - 83.3).abs() < 1e-12);
    assert!(matches!(s(&["V=I000"]), Speed::Unread(w) if w.contains("variable")));
    assert!(matches!(s(&["VR=30.0"]), Speed::Unread(w) if w.contains("orientation")));
    assert!(matches!(s(&["PL=0"]), Speed::Unread(_)));
    assert_eq!(inform(5, "MOVJ", &["VJ=50.00"]).unwrap(), Speed::Joint);
    assert!(inform(6, "MOVL", &["V=20000"]).is_err());
}
