//! Progress on stderr for the library's long jobs ([`stiffid::Progress`]): a bar per stage with a
//! total, a spinner with the count done for a stage without one; hidden when stderr is not a
//! terminal.

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::sync::Mutex;
use std::time::Duration;
use stiffid::Progress;

/// One line per stage.
pub struct Bars {
    lines: MultiProgress,
    current: Mutex<Option<ProgressBar>>,
    /// Whether a finished stage keeps its line (the study's steps) or is cleared (a search).
    keep: bool,
}

impl Bars {
    /// Bars that keep each finished stage's line when `keep`, else clear it.
    pub fn new(keep: bool) -> Self {
        Self {
            lines: MultiProgress::new(),
            current: Mutex::new(None),
            keep,
        }
    }
}

impl Progress for Bars {
    /// Ends the current stage, if one is still open (a front end's spinner for a whole job,
    /// replaced by the job's own stages), then begins `what`.
    fn begin(&self, what: &str, total: usize) {
        self.end();
        let bar = match total {
            0 => {
                let style = ProgressStyle::with_template("{spinner} {msg} {elapsed}")
                    .expect("valid template");
                let bar = ProgressBar::new_spinner()
                    .with_style(style)
                    .with_message(what.to_string());
                bar.enable_steady_tick(Duration::from_millis(100));
                self.lines.add(bar)
            }
            _ => {
                let style =
                    ProgressStyle::with_template("{msg:32} [{bar:30}] {pos}/{len} {elapsed}")
                        .expect("valid template")
                        .progress_chars("=> ");
                let bar = ProgressBar::new(total as u64).with_message(what.to_string());
                self.lines.add(bar.with_style(style))
            }
        };
        *self.current.lock().expect("progress lock") = Some(bar);
    }

    fn advance(&self, done: usize) {
        if let Some(bar) = self.current.lock().expect("progress lock").as_ref() {
            // A spinner shows its count once it has one.
            if bar.length().is_none() && bar.position() == 0 && done > 0 {
                let style = ProgressStyle::with_template("{spinner} {msg} {pos} {elapsed}")
                    .expect("valid template");
                bar.set_style(style);
            }
            bar.set_position(done as u64);
        }
    }

    fn end(&self) {
        if let Some(bar) = self.current.lock().expect("progress lock").take() {
            match self.keep {
                true => bar.finish(),
                false => bar.finish_and_clear(),
            }
        }
    }
}
