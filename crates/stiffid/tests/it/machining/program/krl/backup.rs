//! A KRL program with its controller's backup: the module's `.dat` and `$config.dat`'s tool and
//! base tables read from it; a table entry the setup gives otherwise refused naming both.

use nalgebra::{Isometry3, Vector3};
use stiffid::internal::machining::program::{self, cartesian::Frame, Dialect};
use stiffid::internal::setup::NumberedFrames;
use stiffid::Error;

const SRC: &str = "DEF cell( )\nFDAT_ACT = FP1\nBAS(#PTP_PARAMS, 100)\nPTP XP1\nEND\n";
const DAT: &str = "DEFDAT cell\nDECL FDAT FP1={TOOL_NO 1,BASE_NO 2,IPO_FRAME #BASE}\nDECL E6POS XP1={X 10,Y 20,Z 30,A 0,B 0,C 0,S 2,T 0}\nENDDAT\n";
const CONFIG: &str = "DEFDAT $CONFIG PUBLIC\n;tables\nTOOL_DATA[1]={X 0.0,Y 0.0,Z 250.0,A 0.0,B 0.0,C 0.0}\nBASE_DATA[2]={X 680.0,Y 1000.0,Z 0.0,A 90.0,B 0.0,C 0.0}\nENDDAT\n";

fn backup() -> Vec<(String, String)> {
    vec![
        ("KRC/R1/Program/CELL.DAT".to_string(), DAT.to_string()),
        ("KRC/R1/System/$config.dat".to_string(), CONFIG.to_string()),
    ]
}

#[test]
fn the_module_dat_and_config_tables_come_from_the_backup() {
    // Alone: the point is in no file given.
    assert!(matches!(
        program::parse(SRC, Dialect::Krl),
        Err(Error::Program { line: 4, .. })
    ));
    let files = backup();
    let context = program::Context::default().with_backup(&files);
    let p = program::parse_in(SRC, Dialect::Krl, &context).unwrap();
    let c = p.targets[0].cartesian.as_deref().unwrap();
    assert!((c.position_mm - Vector3::new(10.0, 20.0, 30.0)).norm() < 1e-12);
    // TOOL_DATA[1] and BASE_DATA[2] of $config.dat, its lines 3 and 4.
    match (&c.tool, &c.frame) {
        (Frame::Stated(3, t), Frame::Stated(4, b)) => {
            assert!((t.translation.vector - Vector3::new(0.0, 0.0, 0.25)).norm() < 1e-12);
            assert!((b.translation.vector - Vector3::new(0.68, 1.0, 0.0)).norm() < 1e-12);
            assert!((b.rotation.angle() - 90f64.to_radians()).abs() < 1e-12);
        }
        other => panic!("{other:?}"),
    }
    // The setup's table agreeing: read; disagreeing: refused naming both.
    let agree =
        NumberedFrames::new("tools", &[(1, Isometry3::translation(0.0, 0.0, 0.25))]).unwrap();
    let other =
        NumberedFrames::new("tools", &[(1, Isometry3::translation(0.0, 0.0, 0.3))]).unwrap();
    let with = |tools| program::Context {
        tool: Some((Isometry3::translation(0.0, 0.0, 0.25), tools)),
        ..context
    };
    assert!(program::parse_in(SRC, Dialect::Krl, &with(&agree)).is_ok());
    match program::parse_in(SRC, Dialect::Krl, &with(&other)) {
        Err(Error::InvalidField { field, message }) => {
            assert_eq!(field, "controller.tools");
            assert!(
                message.contains("$config.dat line 3") && message.contains("TOOL_DATA[1]"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}
