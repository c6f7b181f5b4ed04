//! The arguments of a RAPID call or aggregate: split at the commas outside brackets,
//! parentheses, an element's braces (`pts{i, j}`) and strings.

/// The byte ranges of the comma-separated arguments of `args` outside brackets, parentheses
/// and strings.
pub(crate) fn top_level(args: &str) -> Vec<std::ops::Range<usize>> {
    let (mut out, mut depth, mut in_string, mut from) = (Vec::new(), 0i32, false, 0);
    for (i, c) in args.char_indices() {
        match c {
            '"' => in_string = !in_string,
            '[' | '(' | '{' if !in_string => depth += 1,
            ']' | ')' | '}' if !in_string => depth -= 1,
            ',' if !in_string && depth == 0 => {
                out.push(from..i);
                from = i + 1;
            }
            _ => {}
        }
    }
    out.push(from..args.len());
    out
}

/// `args` with each comma that sets an optional argument (`\Name` or `\Name:=value`) apart from
/// the argument before it replaced by a space, outside brackets, parentheses and strings, the
/// byte offsets those of `args`: RAPID reads `tool1 \WObj:=wobj1` and `tool1, \WObj:=wobj1`
/// alike (an optional argument may follow a comma; RoboDK's ABB post writes it so), so the
/// positional arguments are the same whichever the program writes.
pub(crate) fn switches_joined(args: &str) -> String {
    let (mut out, mut depth, mut in_string) = (String::with_capacity(args.len()), 0i32, false);
    for (i, c) in args.char_indices() {
        match c {
            '"' => in_string = !in_string,
            '[' | '(' | '{' if !in_string => depth += 1,
            ']' | ')' | '}' if !in_string => depth -= 1,
            ',' if !in_string && depth == 0 && args[i + 1..].trim_start().starts_with('\\') => {
                out.push(' ');
                continue;
            }
            _ => {}
        }
        out.push(c);
    }
    out
}
