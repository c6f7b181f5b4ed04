//! The free variables' ranges and steps (`crate::compensate::variables`).

use crate::compensate::variables::*;

#[test]
fn ranges_and_steps_are_checked_at_their_limits_in_si() {
    let station = FreeRange::checked(&Variable::Station, 500.0, 10.0).unwrap();
    assert_eq!((station.range, station.step), (0.5, 0.01));
    let rotation = FreeRange::checked(&Variable::ToolRotation, 180.0, 90.0).unwrap();
    assert_eq!(rotation.range, std::f64::consts::PI);
    for (variable, range, step) in [
        (Variable::ToolRotation, 180.1, 2.0),
        (Variable::ToolRotation, 90.0, 90.1),
        (Variable::ToolRotation, 90.0, 5e-324),
        (Variable::Station, 20_001.0, 10.0),
        (Variable::Station, 100.0, 0.09),
        (Variable::Station, 100.0, 100.1),
        (Variable::Positioner, 0.005, 0.01),
        (Variable::Tilt, 10.0, f64::NAN),
        (Variable::Tilt, f64::INFINITY, 1.0),
    ] {
        assert!(
            FreeRange::checked(&variable, range, step).is_err(),
            "{variable:?} {range} {step}"
        );
    }
    assert!(LeadTilt::checked(Some(30.1), 1.0).is_err());
    assert!(LeadTilt::checked(Some(5.0), 5.1).is_err());
    assert!(LeadTilt::checked(None, 30.0).is_ok());
    assert!(LeadTilt::checked(None, 30.1).is_err());
}

#[test]
fn the_rotation_grid_splits_a_step_into_cells_of_at_most_5_deg() {
    let f = FreeRange::checked(&Variable::ToolRotation, 90.0, 12.0).unwrap();
    let (spacing, cells) = f.cells();
    assert_eq!(cells, 3);
    assert!((spacing.to_degrees() - 4.0).abs() < 1e-12);
    assert_eq!(f.angles().len(), 45);
    assert_eq!(f.angle_count(), 45.0);
    assert_eq!(f.angles()[22], 0.0);
}

#[test]
fn the_surge_is_the_tool_rotations_alone() {
    let rotation = FreeRange::checked(&Variable::ToolRotation, 90.0, 2.0).unwrap();
    let free = FreeVariables::new(
        vec![Free::ToolRotation(rotation)],
        Objective::Surge,
        Aggregate::Sum,
    );
    assert!(free.validate().is_ok());
    let mut with_station = free.clone();
    let station = FreeRange::checked(&Variable::Station, 100.0, 10.0).unwrap();
    with_station.free.push(Free::Station(station));
    assert!(with_station.validate().is_err());
}

#[test]
fn the_free_variables_are_one_list_each_found_by_its_kind_and_given_once() {
    let rotation = FreeRange::checked(&Variable::ToolRotation, 90.0, 2.0).unwrap();
    let table = FreeRange::checked(&Variable::Positioner, 45.0, 5.0).unwrap();
    let lean = LeadTilt::checked(Some(10.0), 2.0).unwrap();
    let free = FreeVariables::new(
        vec![
            Free::Positioner(table),
            Free::ToolRotation(rotation),
            Free::LeadTilt(lean),
        ],
        Objective::Bound,
        Aggregate::Max,
    );
    assert!(free.validate().is_ok());
    assert_eq!(free.tool_rotation(), Some(rotation));
    assert_eq!(free.positioner(), Some(table));
    assert_eq!(free.lead_tilt(), Some(lean));
    assert_eq!(
        (free.station(), free.tilt(), free.configuration()),
        (None, None, None)
    );
    assert!(free.frees_external() && free.frees_tool_axis() && free.any());
    let names: Vec<&str> = free.free.iter().map(Free::name).collect();
    assert_eq!(names, ["positioner", "tool-rotation", "lead-tilt"]);
    let inside = free.keeping(|f| !f.is_external());
    assert_eq!(
        inside.free,
        [Free::ToolRotation(rotation), Free::LeadTilt(lean)]
    );
    assert!(!inside.frees_external());
    // Two of one variable (two tables) are refused naming it, whatever their ranges.
    let other = FreeRange::checked(&Variable::Positioner, 10.0, 5.0).unwrap();
    let mut twice = free.clone();
    twice.free.push(Free::Positioner(other));
    let e = twice.validate().unwrap_err().to_string();
    assert!(e.contains("positioner: given twice"), "{e}");
    // A range outside its variable's limits built by hand is refused as the parser refuses it.
    let wide = FreeRange {
        range: 181f64.to_radians(),
        step: 1f64.to_radians(),
    };
    let e = FreeVariables::new(
        vec![Free::ToolRotation(wide)],
        Objective::Bound,
        Aggregate::Sum,
    )
    .validate()
    .unwrap_err()
    .to_string();
    assert!(e.contains("181"), "{e}");
}
