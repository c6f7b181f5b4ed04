//! A KRL declaration that lists several points without values (`DECL POS xKey, xAway, xTop`,
//! as a milling cell's routines declare their run-time points): each name is declared, so a
//! motion to one is refused for its value being the run's, naming the line that assigns it,
//! never as a point no file declares.

use stiffid::internal::machining::program::{self, Dialect};
use stiffid::Error;

const SRC: &str = "DEF mill( )\nDECL POS xKey, xAway[2], xTop\nDECL E6POS xStart={X 0,Y -100,Z 5,A 0,B 0,C 180,S 'B010',T 'B101001'}\n$TOOL = {X 0,Y 0,Z 250,A 0,B 0,C 0}\n$BASE = {X 2000,Y 0,Z 550,A 0,B 0,C 0}\nLIN xStart\nxTop = xStart:{X 0,Y 0,Z 50,A 0,B 0,C 0}\nLIN xTop C_DIS\nEND\n";

#[test]
fn every_point_a_declaration_lists_is_declared() {
    match program::parse(SRC, Dialect::Krl) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 8, "{message}");
            assert!(message.contains("xTop is assigned on line 7"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    // Without the assignment: declared on line 2 without a value.
    let unset = SRC.replace("xTop = xStart:{X 0,Y 0,Z 50,A 0,B 0,C 0}\n", "");
    match program::parse(&unset, Dialect::Krl) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 7, "{message}");
            assert!(
                message.contains("XTOP is declared on line 2 without a value"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}
