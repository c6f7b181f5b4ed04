use stiffid_core::io::readings::{header, parse};

fn read(body: &str, dirs: &str) -> stiffid_core::Result<stiffid_core::io::readings::Readings> {
    let robot = stiffid_core::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
    parse(&format!("{},{dirs}\n{body}", header()), &robot, 4)
}

const ALL: &str = "dir1,dir2,dir3,dir4,dir5,dir6";

#[test]
fn directions_are_read_per_joint() {
    let r = read("a,1,0,0,-90,0,0,0,1,2,3,1,-1,+1,1,-1,-1\n", ALL).unwrap();
    let d = r.readings[0].direction.unwrap();
    assert_eq!(d.as_slice(), &[1.0, -1.0, 1.0, 1.0, -1.0, -1.0]);
    let robot = stiffid_core::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
    let plain = format!("{}\na,1,0,0,-90,0,0,0,1,2,3\n", header());
    assert_eq!(
        parse(&plain, &robot, 4).unwrap().readings[0].direction,
        None
    );
}

#[test]
fn bad_directions_are_refused_naming_line_and_column() {
    let e = read("a,1,0,0,-90,0,0,0,1,2,3,1,0,1,1,1,1\n", ALL).unwrap_err();
    assert_eq!(
        e.to_string(),
        "line 2, column 13 (dir2): '0': expected -1 or +1 (the sign of the joint's last motion)"
    );
    let e = read("a,1,0,0,-90,0,0,0,1,2,3,1,1,1,1,1,1.0\n", ALL).unwrap_err();
    assert!(e.to_string().contains("column 17 (dir6): '1.0'"), "{e}");
    let e = read("a,1,0,0,-90,0,0,0,1,2,3,1,1\n", "dir1,dir3").unwrap_err();
    assert!(e.to_string().contains("missing column 'dir2'"), "{e}");
    let body = "a,1,0,0,-90,0,0,0,1,2,3,1,1,1,1,1,1\na,2,0,0,-90,0,0,0,1,2,3,1,1,-1,1,1,1\n";
    let e = read(body, ALL).unwrap_err();
    assert!(
        e.to_string()
            .contains("line 3, column 1 (posture): posture 'a' has other directions on line 2"),
        "{e}"
    );
}
