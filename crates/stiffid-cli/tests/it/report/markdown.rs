//! The Markdown report's text (`stiffid_cli::report::markdown`).

use stiffid_cli::report::markdown::inline;

#[test]
fn html_in_text_is_escaped_but_code_spans_are_kept() {
    assert_eq!(
        inline("setup <script>x</script> & `a<b`"),
        "setup &lt;script&gt;x&lt;/script&gt; &amp; `a<b`"
    );
}
