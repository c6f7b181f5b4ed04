//! The FANUC measurement file in stiffid's format is the conversion of the original files shipped
//! beside it (`examples/data/fanuc-r2000ic-165f/original/`: rad, N, m), value for value.

use std::path::PathBuf;

fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/data/fanuc-r2000ic-165f")
}

/// The rows of a CSV file under `data_dir()` after its header, as numbers.
fn numbers(relative: &str) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(data_dir().join(relative)).expect(relative);
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(|v| v.trim().parse().expect(v)).collect())
        .collect()
}

fn assert_close(converted: f64, expected: f64, what: &str) {
    let tol = 1e-12 * expected.abs().max(1e-9);
    assert!(
        (converted - expected).abs() <= tol,
        "{what}: {converted} != {expected}"
    );
}

#[test]
fn measurements_are_the_original_files_in_mm_and_degrees() {
    let q = numbers("original/joint_angles.csv");
    let f = numbers("original/forces.csv");
    let d = numbers("original/deltaX.csv");
    let converted = numbers("measurements.csv");
    assert_eq!(q.len(), 43);
    assert_eq!((f.len(), d.len(), converted.len()), (43, 43, 43));
    for (i, row) in converted.iter().enumerate() {
        assert_eq!(row.len(), 14, "row {}", i + 1);
        assert_eq!((row[0], row[1]), ((i + 1) as f64, 1.0), "posture, point");
        for j in 0..6 {
            assert_close(row[2 + j], q[i][j].to_degrees(), "q_deg");
        }
        for a in 0..3 {
            assert_eq!(row[8 + a], f[i][a], "force in N, row {}", i + 1);
            assert_close(row[11 + a], d[i][a] * 1000.0, "displacement in mm");
        }
    }
}
