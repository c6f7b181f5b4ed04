use crate::common::stop::*;

#[test]
fn names_are_the_documents_strings() {
    for stop in Stop::ALL {
        let json = serde_json::to_value(stop).unwrap();
        assert_eq!(json, serde_json::json!(stop.name()));
        assert_eq!(stop.to_string(), stop.name());
    }
    let names: Vec<&str> = Stop::ALL.iter().map(|s| s.name()).collect();
    assert_eq!(
        names,
        [
            "converged",
            "stalled",
            "damping-exhausted",
            "iteration-limit"
        ]
    );
}
