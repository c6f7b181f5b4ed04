//! The compensate text's line of the axes' speed limits at the program's feed, from its
//! document ([`stiffid::app::compensate::speed::SpeedLimits`]).

use stiffid::app::compensate::speed::{AxisSpeed, SpeedLimits};
use stiffid::internal::common::words::count;

/// One line: why the moves were not checked, or the highest share of an axis's speed at the
/// path's own values and at those chosen, with its axis and line, and the moves whose
/// programmed speed is not read.
pub fn line(s: &SpeedLimits) -> String {
    if let Some(why) = &s.not_checked_because {
        return format!("axis speeds at the feed: not checked ({why})\n");
    }
    let highest = |share: fn(&AxisSpeed) -> Option<f64>, line: fn(&AxisSpeed) -> Option<u64>| {
        let top = (s.axes.iter())
            .filter_map(|a| share(a).map(|v| (v, a)))
            .max_by(|x, y| x.0.total_cmp(&y.0));
        match top {
            None => "none".to_string(),
            Some((v, a)) => match line(a) {
                Some(l) => format!("{v:.2} ({} at line {l})", a.axis),
                None => format!("{v:.2}"),
            },
        }
    };
    let unread = match s.moves_not_read {
        0 => String::new(),
        n => format!(
            "; {} not checked (the programmed speed not read)",
            count(n, "linear move")
        ),
    };
    format!(
        "axis speeds at the feed: highest share of an axis's largest speed {} along the path's own values, {} along those chosen{unread}\n",
        highest(|a| a.own_highest_share, |a| a.own_line),
        highest(|a| a.chosen_highest_share, |a| a.chosen_line),
    )
}
