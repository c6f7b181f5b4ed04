//! A run interrupted by `SIGINT` (Ctrl-C), `SIGTERM` or `SIGHUP` leaves the folders as they were:
//! a thread waits for the three signals and, on the first, removes every temporary file and
//! directory of the run ([`crate::output::staged::interrupted`]) and exits with the shell's code
//! for the signal, 128 + its number (130, 143, 129). `SIGKILL` cannot be caught: the next run
//! writing into the same directory removes what such a run left
//! ([`stiffid::internal::io::output::temporary`]).

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use std::sync::Once;

/// Installs the handler (module docs), once per process. Where it cannot be installed the run
/// goes on with the default handlers.
pub fn remove_temporaries_on_signals() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
            return;
        };
        let _ = std::thread::Builder::new()
            .name("stiffid-signals".into())
            .spawn(move || {
                if let Some(signal) = signals.forever().next() {
                    crate::output::staged::interrupted();
                    std::process::exit(128 + signal);
                }
            });
    });
}
