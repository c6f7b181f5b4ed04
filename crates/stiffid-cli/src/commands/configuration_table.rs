//! The text table of `stiffid compensate --free-configuration`: every configuration of the arm, its
//! objective or why it cannot take the path, and the one chosen.

use stiffid::app::compensate::configurations::ConfigurationsDocument;

/// The table of the document's configurations.
pub fn table(c: &ConfigurationsDocument) -> String {
    let mut text = format!(
        "free configuration (minimising the {} of the {}): {} chosen{}\n  {:<34} {:<16} {:>12} {:>12}\n",
        c.aggregate,
        c.objective,
        c.chosen,
        match &c.own {
            Some(own) if *own == c.chosen => " (the path's own)".to_string(),
            Some(own) => format!(" (the path's own: {own})"),
            None => " (the start posture reaches no posture at the first point)".to_string(),
        },
        "configuration",
        "FANUC",
        "sum mm",
        "max mm"
    );
    for r in &c.configurations {
        let value = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
        let mark = match (r.chosen, r.own) {
            (true, true) => "chosen, own",
            (true, false) => "chosen",
            (false, true) => "own",
            (false, false) => "",
        };
        let refused = match (&r.failed_because, r.failed_line) {
            (Some(why), Some(line)) => format!("refused at line {line}: {why}"),
            (Some(why), None) => format!("refused: {why}"),
            _ => String::new(),
        };
        text += &format!(
            "  {:<34} {:<16} {:>12} {:>12}  {}\n",
            r.name,
            r.fanuc,
            value(r.sum_mm),
            value(r.max_mm),
            [mark, &refused]
                .iter()
                .filter(|s| !s.is_empty())
                .copied()
                .collect::<Vec<_>>()
                .join("; ")
        );
    }
    text
}
