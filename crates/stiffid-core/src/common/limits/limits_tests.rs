use crate::common::limits::*;

#[test]
fn one_line_cuts_long_words_and_long_messages() {
    let field = "x".repeat(5_000_000);
    let m = one_line(&format!(
        "TOML parse error at line 1\n  |\n1 | name = \"{field}\"\n"
    ));
    assert!(
        m.starts_with("TOML parse error at line 1 1 | name ="),
        "{m}"
    );
    assert!(m.len() < 200, "{}", m.len());
    let many = "word ".repeat(1000);
    assert_eq!(one_line(&many).chars().count(), MAX_MESSAGE_CHARS + 3);
}
