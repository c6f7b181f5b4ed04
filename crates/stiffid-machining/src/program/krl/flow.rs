//! KRL's loops, branches and jumps around a program's motions (module docs of [`super`]): a
//! motion inside `IF`, `SWITCH`, `FOR`, `WHILE`, `REPEAT` or `LOOP` runs as many times as the
//! run decides, and a `GOTO` changes the order, so both are refused naming the line; loops and
//! branches that hold no motion (waits, signals, counters) run as written.

/// The constructs open at a line of the program.
#[derive(Debug, Default)]
pub(super) struct Flow {
    /// Each open construct, outermost first: its word and line.
    open: Vec<(String, u64)>,
    /// The first `GOTO`'s line.
    pub jump: Option<u64>,
}

impl Flow {
    /// Reads the line `line` whose first word (upper case) is `first`.
    pub(crate) fn line(&mut self, line: u64, first: &str) {
        match first {
            "IF" | "SWITCH" | "FOR" | "WHILE" | "REPEAT" | "LOOP" => {
                self.open.push((first.to_string(), line));
            }
            "ENDIF" | "ENDSWITCH" | "ENDFOR" | "ENDWHILE" | "UNTIL" | "ENDLOOP" => {
                self.open.pop();
            }
            "GOTO" => {
                self.jump.get_or_insert(line);
            }
            "DEF" | "DEFFCT" | "END" | "ENDFCT" => self.open.clear(),
            _ => {}
        }
    }

    /// The outermost construct open, if any: its word and line.
    pub(crate) fn inside(&self) -> Option<&(String, u64)> {
        self.open.first()
    }
}
