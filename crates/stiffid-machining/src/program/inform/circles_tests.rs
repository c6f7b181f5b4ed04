//! The via points of a job's circles (`circles`): each `MOVC` target between two other `MOVC`
//! targets is one, fed along the circle's tangent; a lone pair of `MOVC` is none.

use crate::program::{parse_in, Context, Dialect};
use stiffid_core::setup::Pulses;

#[test]
fn each_movc_between_two_others_is_a_via_point() {
    let pulses = Pulses {
        per_deg: [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7],
        external: Vec::new(),
    };
    let context = Context {
        pulses: Some(&pulses),
        ..Context::default()
    };
    let pos: String = (0..7)
        .map(|k| format!("C{k:05}={},2000,3000,0,-4500,500\r\n", 1000 + 100 * k))
        .collect();
    let words = ["MOVJ", "MOVC", "MOVC", "MOVC", "MOVL", "MOVC", "MOVC"];
    let inst: String = (words.iter().enumerate())
        .map(|(k, w)| format!("{w} C{k:05} V=10.0\r\n"))
        .collect();
    let job = format!(
        "/JOB\r\n//NAME C\r\n//POS\r\n///NPOS 7,0,0,0,0,0\r\n{pos}//INST\r\nNOP\r\n{inst}END\r\n"
    );
    let read = parse_in(&job, Dialect::Inform, &context).unwrap();
    let via: Vec<bool> = read.targets.iter().map(|t| t.via).collect();
    assert_eq!(via, [false, false, true, false, false, false, false]);
}
