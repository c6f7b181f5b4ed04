//! Identification from a measurement file read in chunks, once (`identify::streamed`), against
//! the in-memory paths: the parsed file's `identify::least_squares` (the same bits) and the
//! one-shot QR of the whole `Psi` (`Observations::least_squares`, to 1e-12 relative); the same
//! bits with 1 and 2 threads; errors that name the line and column of a row far into the file.

use crate::common;
use stiffid::internal::identify::Identify;

use common::{assert_close, measurement_csv, noisy};
use stiffid::internal::identify::{self, streamed, Identification};
use stiffid::internal::io::measurements::{self, Labels};
use stiffid::internal::observation::Observations;
use stiffid::{internal::setup, ColumnProblem, Error, Setup};

/// The piece the measurement reader reads at a time, bytes (512 KiB).
const PIECE_BYTES: usize = 1 << 19;

const FANUC: &str = include_str!("../../../../examples/data/fanuc-r2000ic-165f/measurements.csv");

/// The streamed identification of `text`.
fn streamed(setup: &Setup, text: &str) -> stiffid::Result<(Identification, streamed::Rows)> {
    streamed::least_squares(setup, text.as_bytes())
}

/// The one-shot QR of the whole `Psi` of the parsed `text`.
fn whole(setup: &Setup, text: &str) -> Identification {
    let mut file = measurements::parse(text).unwrap();
    file.to_base_frame(setup).unwrap();
    Observations::from_measurements(setup.arm(), &file.measurements)
        .unwrap()
        .least_squares()
        .unwrap()
}

/// A measurement file of `n` random postures x 4 points under random wrenches (paper setup),
/// noisy, with moments; labels `pose {i}`.
fn synthetic_file(setup: &Setup, n: usize, seed: u64) -> String {
    "# generated\n".to_string() + &measurement_csv(&noisy(setup, n, seed))
}

/// `identify::least_squares` of the parsed `text` in the base frame.
fn parsed(setup: &Setup, text: &str) -> (Identification, measurements::MeasurementFile) {
    let mut file = measurements::parse(text).unwrap();
    file.to_base_frame(setup).unwrap();
    let id = identify::least_squares(setup.arm(), &file.measurements).unwrap();
    (id, file)
}

#[test]
fn the_fanuc_file_streamed_equals_the_in_memory_fits() {
    let setup = setup::builtin("fanuc-r2000ic-165f").unwrap();
    // The forces in the base frame (their moments zero are not kept), and as if in the tool
    // frame (the whole wrench kept).
    let tool = FANUC.replacen("fx_n,fy_n,fz_n", "fx_tool_n,fy_tool_n,fz_tool_n", 1);
    for text in [FANUC, &tool] {
        let (id, rows) = streamed(&setup, text).unwrap();
        assert_close(&id, &whole(&setup, text));
        let (exact, file) = parsed(&setup, text);
        assert_eq!(id, exact);
        assert_eq!(
            id.residuals.map(f64::to_bits),
            exact.residuals.map(f64::to_bits)
        );
        assert_eq!(rows.lines, file.lines);
        let labels: Vec<&str> = rows.labels.iter().collect();
        assert_eq!(labels, file.labels);
        assert_eq!(rows.label(0), file.labels[file.measurements[0].posture]);
    }
}

#[test]
fn a_file_of_many_chunks_streamed_equals_the_one_shot_qr_with_one_and_two_threads() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let text = synthetic_file(&setup, 6000, 5);
    // Several chunks of several pieces.
    assert!(text.len() > 12 * PIECE_BYTES);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| streamed(&setup, &text).unwrap())
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one, two);
    assert_eq!(
        one.0.compliance.map(f64::to_bits),
        two.0.compliance.map(f64::to_bits)
    );
    assert_eq!((one.0.rows, one.0.postures), (72_000, 6000));
    assert_eq!(one.1.lines[0], 3);
    assert_eq!(one.1.label(23_999), "pose 5999");
    assert_close(&one.0, &whole(&setup, &text));
    let exact = parsed(&setup, &text).0;
    assert_eq!(
        one.0.residuals.map(f64::to_bits),
        exact.residuals.map(f64::to_bits)
    );
}

#[test]
fn errors_far_into_a_streamed_file_name_their_line_and_column() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let text = synthetic_file(&setup, 3000, 6);
    let lines: Vec<&str> = text.lines().collect();
    let with_line = |n: usize, new: String| {
        let mut l: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        l[n - 1] = new;
        l.join("\n") + "\n"
    };
    // A field that is not a number in line 11 000 (a later chunk): column 9 (fx_n).
    let mut fields: Vec<String> = lines[10_999].split(',').map(str::to_string).collect();
    fields[8] = "abc".into();
    match streamed(&setup, &with_line(11_000, fields.join(","))).unwrap_err() {
        Error::Column {
            line: 11_000,
            column: Some(9),
            problem: ColumnProblem::NotANumber { .. },
            ..
        } => {}
        e => panic!("{e}"),
    }
    // A posture of line 3 measured again at other angles on line 11 000: the checks run over
    // the chunks.
    let mut fields: Vec<String> = lines[10_999].split(',').map(str::to_string).collect();
    fields[0] = "pose 0".into();
    match streamed(&setup, &with_line(11_000, fields.join(","))).unwrap_err() {
        Error::Column {
            line: 11_000,
            column: Some(1),
            problem: ColumnProblem::Measurement { message },
            ..
        } => assert!(message.contains("measurement 1"), "{message}"),
        e => panic!("{e}"),
    }
}

#[test]
fn labels_are_numbered_in_order_of_first_appearance() {
    let labels: Labels = ["b", "a", "b", "c", "a"].into_iter().collect();
    assert_eq!(labels.iter().collect::<Vec<_>>(), ["b", "a", "c"]);
    let text = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,dx_mm,dy_mm,dz_mm\n\
                b,1,0,0,0,0,-90,0,0,0,-100,0,0,-0.1\n\
                a,1,0,10,0,0,-90,0,0,0,-100,0,0,-0.1\n\
                b,2,0,0,0,0,-90,0,0,0,-100,0,0,-0.1\n";
    let file = measurements::parse(text).unwrap();
    let postures: Vec<usize> = file.measurements.iter().map(|m| m.posture).collect();
    assert_eq!(
        (postures, file.labels),
        (vec![0, 1, 0], vec!["b".to_string(), "a".into()])
    );
    // A quoted label with a line break: an error at its line, not a silent join.
    let broken = text.replacen("a,1", "\"a\nx\",1", 1);
    match measurements::parse(&broken).unwrap_err() {
        Error::Column {
            line: 3,
            column: Some(1),
            problem: ColumnProblem::Unreadable { message },
            ..
        } => assert!(message.contains("line break"), "{message}"),
        e => panic!("{e}"),
    }
}

#[test]
fn a_chunk_of_nothing_but_comments_does_not_end_the_file() {
    let setup = setup::builtin("fanuc-r2000ic-165f").unwrap();
    // More than a chunk (8 pieces) of comment lines between rows 10 and 11.
    let comments = "# a comment\n".repeat(10 * PIECE_BYTES / 12);
    let mut lines: Vec<&str> = FANUC.lines().collect();
    lines.insert(11, comments.trim_end());
    let text = lines.join("\n") + "\n";
    let file = measurements::parse(&text).unwrap();
    assert_eq!(file.measurements.len(), 43);
    let extra = comments.lines().count() as u64;
    assert_eq!((file.lines[9], file.lines[10]), (11, 12 + extra));
    let (id, rows) = streamed(&setup, &text).unwrap();
    assert_eq!(rows.lines, file.lines);
    assert_close(&id, &whole(&setup, FANUC));
}

#[test]
fn lines_are_right_in_a_file_with_crlf_line_ends_on_either_parsing_path() {
    let setup = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let crlf = FANUC.replace('\n', "\r\n");
    // A quoted label sends its piece to the csv path; plain text takes the fast one.
    let quoted = crlf.replacen("\r\n9,1,", "\r\n\"9\",1,", 1);
    let (lf, lf_rows) = streamed(&setup, FANUC).unwrap();
    for text in [&crlf, &quoted] {
        let (id, rows) = streamed(&setup, text).unwrap();
        assert_eq!(id, lf);
        assert_eq!(rows.lines, lf_rows.lines);
        // A bad measuring point on line 10 (posture 9) is named on line 10.
        let bad = text.replacen(",1,-51.547", ",1x,-51.547", 1);
        assert_ne!(&bad, text);
        match streamed(&setup, &bad).unwrap_err() {
            Error::Column {
                line: 10,
                column: Some(2),
                ..
            } => {}
            e => panic!("{e}"),
        }
    }
}

#[test]
fn a_row_after_blank_lines_is_named_by_its_own_line_on_either_parsing_path() {
    let setup = setup::builtin("fanuc-r2000ic-165f").unwrap();
    // Three blank lines before posture 9 (line 10, now 13); csv's own count said 10.
    let blank = FANUC.replacen("\n9,1,", "\n\n\n\n9,1,", 1);
    let quoted = blank.replacen("\n2,1,", "\n\"2\",1,", 1);
    for text in [&blank, &quoted] {
        let (_, rows) = streamed(&setup, text).unwrap();
        assert_eq!(rows.lines[7..9], [9, 13]);
        let bad = text.replacen(",1,-51.547", ",1x,-51.547", 1);
        match streamed(&setup, &bad).unwrap_err() {
            Error::Column { line: 13, .. } => {}
            e => panic!("{e}"),
        }
    }
}
