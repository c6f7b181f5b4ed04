//! The text table of `stiffid compensate --free configuration`: every configuration of the arm, its
//! objective or why it cannot take the path, and the one chosen; per run, each run's choice.

use stiffid::app::compensate::configurations::{ConfigurationsDocument, RunRow};

/// A length in mm with four decimals, `-` for none.
fn value(v: Option<f64>) -> String {
    v.map_or("-".to_string(), |v| format!("{v:.4}"))
}

/// The table of the document's configurations, and per run the runs'.
pub fn table(c: &ConfigurationsDocument) -> String {
    match c.runs.is_empty() {
        true => program(c),
        false => runs(c),
    }
}

/// The table of one configuration per program.
fn program(c: &ConfigurationsDocument) -> String {
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
            r.configuration_data.get("ls").map_or("", String::as_str),
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

/// The table of one configuration per run: each run's lines, choice and objective beside its
/// own configuration's.
fn runs(c: &ConfigurationsDocument) -> String {
    let moved = c.runs.iter().filter(|r| !r.chosen_own).count();
    let mut text = format!(
        "free configuration per run (minimising the {} of the {}): {} mm over {} runs, {} in another configuration than the program's own\n  {:>4} {:>13} {:<34} {:>12} {:>12} {:>12}\n",
        c.aggregate,
        c.objective,
        value(c.objective_mm),
        c.runs.len(),
        moved,
        "run",
        "lines",
        "configuration",
        "sum mm",
        "max mm",
        "own mm"
    );
    for r in &c.runs {
        text += &row(r);
    }
    text
}

/// One run's line.
fn row(r: &RunRow) -> String {
    format!(
        "  {:>4} {:>13} {:<34} {:>12} {:>12} {:>12}  {}\n",
        r.run,
        format!("{}-{}", r.first_line, r.last_line),
        r.chosen,
        value(r.sum_mm),
        value(r.max_mm),
        value(r.own_objective_mm),
        match (r.chosen_own, &r.own) {
            (true, _) => "own".to_string(),
            (false, Some(own)) => format!("own: {own}"),
            (false, None) => "own reaches no posture".to_string(),
        }
    )
}
