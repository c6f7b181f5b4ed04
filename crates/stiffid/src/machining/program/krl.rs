//! KUKA KRL: `PTP {A1 0, A2 -90, ...}`, `LIN {...}` and `DECL E6AXIS XP1={A1 0,...}` (or
//! `AXIS`) aggregates; `;` starts a comment.

use super::{at, number_at, six, JointTarget};
use crate::Result;

/// Every joint target of `text` (module docs).
pub(crate) fn targets(text: &str) -> Result<Vec<JointTarget>> {
    let mut out = Vec::new();
    for (line, start, l) in super::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        let words: Vec<String> = code
            .split(|c: char| c.is_whitespace() || c == '=' || c == '{')
            .filter(|w| !w.is_empty())
            .map(str::to_ascii_uppercase)
            .collect();
        let first = words.first().map(String::as_str).unwrap_or("");
        let motion = matches!(first, "PTP" | "LIN" | "CIRC" | "SPTP" | "SLIN" | "SCIRC");
        let relative = matches!(first, "PTP_REL" | "LIN_REL" | "CIRC_REL");
        let declared = words.iter().take(4).any(|w| w == "E6AXIS" || w == "AXIS")
            && words.iter().any(|w| w == "DECL")
            || matches!(first, "E6AXIS" | "AXIS");
        let Some(open) = code.find('{') else {
            if relative {
                return Err(at(
                    line,
                    format!(
                        "{first}: a relative motion; stiffid compensates absolute joint targets"
                    ),
                ));
            }
            continue;
        };
        if relative {
            return Err(at(
                line,
                format!("{first}: a relative motion; stiffid compensates absolute joint targets"),
            ));
        }
        if (motion && first.starts_with('C')) || first.starts_with("SC") {
            return Err(at(
                line,
                format!(
                    "{first}: only PTP and LIN motions to absolute joint targets are compensated"
                ),
            ));
        }
        if !motion && !declared {
            continue;
        }
        let close = code[open..]
            .find('}')
            .map(|c| open + c)
            .ok_or_else(|| at(line, "aggregate without its closing '}' on the line".into()))?;
        out.push(aggregate(line, start, code, open + 1, close)?);
    }
    Ok(out)
}

/// The target of the aggregate between `from` and `to` of `code` (which starts at byte `start`).
fn aggregate(line: u64, start: usize, code: &str, from: usize, to: usize) -> Result<JointTarget> {
    let inner = &code[from..to];
    // An optional type: `{E6AXIS: A1 0, ...}`.
    let skip = inner.find(':').map_or(0, |c| c + 1);
    let mut found: [Option<(f64, std::ops::Range<usize>)>; 6] = Default::default();
    let mut at_byte = from + skip;
    for item in code[from + skip..to].split(',') {
        let name_start = at_byte + item.len() - item.trim_start().len();
        let trimmed = item.trim();
        let name: String = trimmed
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect();
        let upper = name.to_ascii_uppercase();
        if matches!(
            upper.as_str(),
            "X" | "Y" | "Z" | "A" | "B" | "C" | "S" | "T"
        ) {
            return Err(at(line, format!("a Cartesian target ({upper}); stiffid compensates joint targets (E6AXIS, AXIS)")));
        }
        if let Some(k) = upper
            .strip_prefix('A')
            .and_then(|d| d.parse::<usize>().ok())
        {
            if (1..=6).contains(&k) {
                let (v, span) = number_at(code, name_start + name.len())
                    .ok_or_else(|| at(line, format!("{name}: expected a number")))?;
                if found[k - 1].is_some() {
                    return Err(at(line, format!("{name} given twice")));
                }
                found[k - 1] = Some((v, start + span.start..start + span.end));
            }
        }
        at_byte += item.len() + 1;
    }
    six(line, found, "A")
}
