//! The arguments of a RAPID call or aggregate: split at the commas outside brackets,
//! parentheses and strings.

/// The byte ranges of the comma-separated arguments of `args` outside brackets, parentheses
/// and strings.
pub(crate) fn top_level(args: &str) -> Vec<std::ops::Range<usize>> {
    let (mut out, mut depth, mut in_string, mut from) = (Vec::new(), 0i32, false, 0);
    for (i, c) in args.char_indices() {
        match c {
            '"' => in_string = !in_string,
            '[' | '(' if !in_string => depth += 1,
            ']' | ')' if !in_string => depth -= 1,
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
