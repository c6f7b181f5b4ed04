//! The external axes' columns of a cell's files (`e1_mm`, `e2_deg`, ...): found in the cell's
//! order, read in SI, gaps, two units and bad values refused.

use stiffid_core::io::external::*;
use stiffid_core::Error;

fn names(header: &str) -> Vec<String> {
    header.split(',').map(str::to_string).collect()
}

#[test]
fn columns_are_found_in_the_cells_order_and_read_in_si() {
    let header = names("q1_deg,e2_deg,e1_mm,x");
    let c = Columns::find(&header, 1).unwrap();
    let row = ["10", "90", "1500", "y"];
    let v = c.values(
        |i| row[i],
        |_, p| Error::InvalidField {
            field: String::new(),
            message: p.to_string(),
        },
    );
    assert_eq!(v.unwrap().as_slice(), [1.5, std::f64::consts::FRAC_PI_2]);
    // The cell's order (e1 in mm, then e2 in deg), whatever the file's; none given, none read.
    let none = Columns::find(&names("q1_deg"), 1).unwrap();
    let v = none.values(
        |i| row[i],
        |_, p| Error::InvalidField {
            field: String::new(),
            message: p.to_string(),
        },
    );
    assert!(v.unwrap().is_empty());
}

#[test]
fn gaps_and_two_units_are_refused() {
    let e = Columns::find(&names("e2_mm"), 3).unwrap_err().to_string();
    assert!(e.contains("e1_mm or e1_deg"), "{e}");
    let e = Columns::find(&names("e1_mm,e1_deg"), 3)
        .unwrap_err()
        .to_string();
    assert!(e.contains("e1_mm") && e.contains("e1_deg"), "{e}");
    let c = Columns::find(&names("e1_mm"), 1).unwrap();
    let bad = |row: [&'static str; 1]| {
        c.values(
            |i| row[i],
            |_, p| Error::InvalidField {
                field: String::new(),
                message: p.to_string(),
            },
        )
        .unwrap_err()
        .to_string()
    };
    assert!(bad(["x"]).contains("not a finite number"));
    assert!(bad(["1e9"]).contains("e1_mm"));
}
