//! Control flow: LinuxCNC's O-words (manual, "O Codes") and FANUC's and Haas's macro
//! statements (`IF [..] GOTO n`, `IF [..] THEN ..`, `GOTO n`, `WHILE [..] DO m`, `END m`).
//! A jump goes to the O-word of the same label (LinuxCNC) or the block `N n` of the program
//! in force, searched forward and then from the program's start (FANUC).

use super::expr::{self, Cursor, Flavour};
use super::line::{self, classify, Stmt};
use super::{shown, Kind, Run};

type Outcome = std::result::Result<(), String>;

impl Run<'_> {
    /// A LinuxCNC O-word.
    pub(super) fn o_word(&mut self, label: &str, keyword: &str, rest: &str) -> Outcome {
        if self.flavour == Flavour::Fanuc {
            return Err(format!("{} {keyword}: a LinuxCNC O-word, which FANUC and Haas do not read (the setup's [controller] dialect)", shown(label)));
        }
        let here = self.pc;
        match keyword {
            "sub" => self.pc = self.find(here, label, &["endsub"], "endsub")? + 1,
            "endsub" | "return" => return self.o_return(label),
            "call" => return self.o_call(label, rest),
            "if" => {
                self.ends_at(|r| r.find(here, label, &["endif"], "endif"))?;
                if self.condition(rest)? {
                    self.pc += 1;
                } else {
                    self.next_branch(label)?;
                }
            }
            // A branch done: on past the endif.
            "elseif" | "else" => self.pc = self.find(here, label, &["endif"], "endif")? + 1,
            "while" if self.do_labels.contains(label) => {
                self.pc = match self.condition(rest)? {
                    true => self.find_back(here, label, "do")? + 1,
                    false => here + 1,
                };
            }
            "while" => {
                self.ends_at(|r| r.find(here, label, &["endwhile"], "endwhile"))?;
                self.pc = match self.condition(rest)? {
                    true => here + 1,
                    false => self.find(here, label, &["endwhile"], "endwhile")? + 1,
                };
            }
            "endwhile" => self.pc = self.find_back(here, label, "while")?,
            "repeat" => {
                self.ends_at(|r| r.find(here, label, &["endrepeat"], "endrepeat"))?;
                self.repeat(label, rest)?;
            }
            "do" => {
                self.ends_at(|r| r.find(here, label, &["while"], "while"))?;
                self.pc += 1;
            }
            "endrepeat" => {
                let key = (self.stack.len(), label.to_string());
                if let Some(n) = self.repeats.get_mut(&key) {
                    *n -= 1.0;
                }
                self.pc = self.find_back(here, label, "repeat")?;
            }
            "break" => {
                let end = self.loop_end(label)?;
                self.repeats.remove(&(self.stack.len(), label.to_string()));
                self.pc = end + 1;
            }
            "continue" => self.pc = self.loop_end(label)?,
            _ => self.pc += 1,
        }
        Ok(())
    }

    /// Refuses, the first time the loop or branch at the line in force is entered, one whose
    /// end `find` does not find (a controller alarms on it; run through, the blocks after it
    /// would be read as its body once).
    fn ends_at(
        &mut self,
        find: impl FnOnce(&Self) -> std::result::Result<usize, String>,
    ) -> Outcome {
        if !self.ends_found.contains(&self.pc) {
            find(self)?;
            self.ends_found.insert(self.pc);
        }
        Ok(())
    }

    /// `O.. if` (or `elseif`) false: on to the next `elseif` that holds, the `else`, or past
    /// the `endif`.
    fn next_branch(&mut self, label: &str) -> Outcome {
        let mut at = self.pc;
        loop {
            at = self.find(at, label, &["elseif", "else", "endif"], "endif")?;
            let code = self.codes[at].clone();
            let Ok(Stmt::OWord { keyword, rest, .. }) = classify(&code, &self.store, self.flavour)
            else {
                return Err("an O-word's branch could not be read".into());
            };
            if keyword != "elseif" || self.condition(rest)? {
                self.pc = at + 1;
                return Ok(());
            }
        }
    }

    /// `O.. repeat [n]`: the loop's body run `n` times.
    fn repeat(&mut self, label: &str, rest: &str) -> Outcome {
        let key = (self.stack.len(), label.to_string());
        if !self.repeats.contains_key(&key) {
            let n = self.value(rest)?;
            self.repeats.insert(key.clone(), n.round());
        }
        if self.repeats[&key] > 0.0 {
            self.pc += 1;
        } else {
            self.repeats.remove(&key);
            self.pc = self.find(self.pc, label, &["endrepeat"], "endrepeat")? + 1;
        }
        Ok(())
    }

    /// The line ending the loop `label` (`endwhile`, `endrepeat`, or a `do` loop's `while`).
    fn loop_end(&self, label: &str) -> std::result::Result<usize, String> {
        let ends: &[&str] = match self.do_labels.contains(label) {
            true => &["while"],
            false => &["endwhile", "endrepeat"],
        };
        self.find(self.pc, label, ends, "the end of its loop")
    }

    /// The value of the bracketed expression opening `rest`.
    fn value(&self, rest: &str) -> std::result::Result<f64, String> {
        let mut c = Cursor::new(rest, 0);
        expr::expression(&mut c, &self.store, self.flavour)
    }

    fn condition(&self, rest: &str) -> std::result::Result<bool, String> {
        Ok(self.value(rest)? != 0.0)
    }

    /// The next O-word after `from` with `label` and one of `keywords`.
    pub(super) fn find(
        &self,
        from: usize,
        label: &str,
        keywords: &[&str],
        what: &str,
    ) -> std::result::Result<usize, String> {
        (from + 1..self.codes.len())
            .find(|&i| self.is_o(i, label, keywords))
            .ok_or_else(|| format!("{}: no {what} of the same label after it", shown(label)))
    }

    /// The O-word before `from` with `label` and `keyword`.
    fn find_back(
        &self,
        from: usize,
        label: &str,
        keyword: &str,
    ) -> std::result::Result<usize, String> {
        (0..from)
            .rev()
            .find(|&i| self.is_o(i, label, &[keyword]))
            .ok_or_else(|| format!("{}: no {keyword} of the same label before it", shown(label)))
    }

    fn is_o(&self, i: usize, label: &str, keywords: &[&str]) -> bool {
        matches!(classify(&self.codes[i], &self.store, self.flavour), Ok(Stmt::OWord { label: l, keyword, .. }) if l == label && keywords.contains(&keyword.as_str()))
    }

    /// A FANUC/Haas statement: `IF`, `WHILE`, `DO`, `END`, `GOTO`.
    pub(super) fn fanuc(&mut self, stmt: Stmt) -> Outcome {
        if self.flavour == Flavour::LinuxCnc {
            return Err("IF, WHILE, GOTO, DO and END statements are FANUC's and Haas's macro B, which LinuxCNC does not read (it has O-words: O100 if, O100 while); the setup's [controller] dialect is \"linuxcnc\"".into());
        }
        match stmt {
            Stmt::If(rest) => self.fanuc_if(rest),
            Stmt::While(rest) => {
                let mut c = Cursor::new(rest, 0);
                let holds = expr::expression(&mut c, &self.store, self.flavour)? != 0.0;
                let m = do_number(&rest[c.at..], "DO")?;
                let end = |s: &Stmt| matches!(s, Stmt::End(r) if do_number(r, "").ok() == Some(m));
                self.ends_at(|r| r.fanuc_find(end, &format!("END {m}"), true))?;
                self.pc = match holds {
                    true => self.pc + 1,
                    false => {
                        self.fanuc_find(
                            |s| matches!(s, Stmt::End(r) if do_number(r, "").ok() == Some(m)),
                            &format!("END {m}"),
                            true,
                        )? + 1
                    }
                };
                Ok(())
            }
            Stmt::Do(_) => {
                self.pc += 1;
                Ok(())
            }
            Stmt::End(rest) => {
                let m = do_number(rest, "")?;
                let is_do = |s: &Stmt| match s {
                    Stmt::While(r) => {
                        r.to_ascii_uppercase()
                            .rfind("DO")
                            .and_then(|k| do_number(&r[k + 2..], "").ok())
                            == Some(m)
                    }
                    Stmt::Do(r) => do_number(r, "").ok() == Some(m),
                    _ => false,
                };
                self.pc = self.fanuc_find(is_do, &format!("WHILE [..] DO {m}"), false)?;
                Ok(())
            }
            Stmt::Goto(rest) => self.goto(rest),
            _ => Ok(()),
        }
    }

    /// `IF [..] GOTO n` or `IF [..] THEN ..`.
    fn fanuc_if(&mut self, rest: &str) -> Outcome {
        let mut c = Cursor::new(rest, 0);
        let holds = expr::expression(&mut c, &self.store, self.flavour)? != 0.0;
        let after = rest[c.at..].trim_start();
        let upper = after.to_ascii_uppercase();
        if let Some(target) = upper.strip_prefix("GOTO").map(|_| &after[4..]) {
            return match holds {
                true => self.goto(target),
                false => {
                    self.pc += 1;
                    Ok(())
                }
            };
        }
        let Some(then) = upper.strip_prefix("THEN").map(|_| &after[4..]) else {
            return Err(format!(
                "IF [..] {}: expected GOTO n or THEN",
                stiffid_core::common::limits::short(after)
            ));
        };
        if holds {
            let sub = line::substitute(then, &self.store, self.flavour)?;
            if !sub.text.trim().is_empty() {
                return Err(
                    "IF [..] THEN with a block: stiffid reads THEN with assignments only (#1 = ..)"
                        .into(),
                );
            }
            for (p, v) in &sub.assignments {
                self.store.set(p, *v)?;
            }
        }
        self.pc += 1;
        Ok(())
    }

    /// `GOTO n`: to the block `N n` of the program in force.
    fn goto(&mut self, target: &str) -> Outcome {
        let mut c = Cursor::new(target, 0);
        let n = expr::real_value(&mut c, &self.store, self.flavour)?;
        if n.fract() != 0.0 || n < 0.0 {
            return Err(format!("GOTO {n}: expected a sequence number"));
        }
        let n = n as u32;
        let (start, end) = self.program_range();
        let found = (self.pc + 1..end)
            .chain(start..=self.pc)
            .find(|&i| line::sequence(&self.codes[i]).0 == Some(n));
        self.pc = found.ok_or_else(|| format!("GOTO {n}: no block N{n} in this program"))?;
        Ok(())
    }

    /// The lines of the program in force: from its number line (or the file's start) to the
    /// next program's.
    pub(super) fn program_range(&self) -> (usize, usize) {
        let start = self.stack.last().map_or(0, |f| f.program);
        let mut next: Vec<usize> = self
            .programs
            .values()
            .copied()
            .filter(|&i| i > start && Some(i) != self.own_header)
            .collect();
        next.sort_unstable();
        (start, next.first().copied().unwrap_or(self.codes.len()))
    }

    /// The first statement of the program in force that `is` is true of, forward from the line
    /// after this one (`forward`) or back from it.
    fn fanuc_find(
        &self,
        is: impl Fn(&Stmt) -> bool,
        what: &str,
        forward: bool,
    ) -> std::result::Result<usize, String> {
        let (start, end) = self.program_range();
        let holds =
            |i: &usize| classify(&self.codes[*i], &self.store, self.flavour).is_ok_and(|s| is(&s));
        let found = match forward {
            true => (self.pc + 1..end).find(holds),
            false => (start..self.pc).rev().find(holds),
        };
        found.ok_or_else(|| format!("no {what} for it in this program"))
    }

    /// Whether the call on top of the stack is of `kind`.
    pub(super) fn in_call(&self, kind: &Kind) -> bool {
        self.stack.last().is_some_and(|f| &f.kind == kind)
    }
}

/// The loop number after `keyword` (`DO 1`, `END 1`): 1 to 3 on FANUC (Haas up to 255).
fn do_number(text: &str, keyword: &str) -> std::result::Result<u32, String> {
    let t = text.trim_start();
    let upper = t.to_ascii_uppercase();
    let rest = match keyword {
        "" => t,
        k if upper.starts_with(k) => &t[k.len()..],
        _ => return Err(format!("expected {keyword} m after the condition")),
    };
    rest.trim().parse::<u32>().map_err(|_| {
        format!(
            "'{}': expected a loop number",
            stiffid_core::common::limits::short(rest)
        )
    })
}
