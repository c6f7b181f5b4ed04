//! Why a search stopped (`crate::Termination`).

use crate::Termination;

#[test]
fn names_round_trip_and_are_distinct() {
    for t in Termination::ALL {
        assert_eq!(t.name().parse::<Termination>(), Ok(t));
        assert_eq!(t.to_string(), t.name());
    }
    assert!("stopped".parse::<Termination>().is_err());
    let converged: Vec<_> = Termination::ALL
        .into_iter()
        .filter(|t| t.is_converged())
        .collect();
    assert_eq!(
        converged,
        [Termination::Converged, Termination::StepTolerance]
    );
}
