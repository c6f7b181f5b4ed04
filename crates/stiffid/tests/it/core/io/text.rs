//! An input file's bytes as text: UTF-8 read, the first invalid byte named with its line and
//! column.

#[test]
fn text_reads_utf8_and_names_the_first_invalid_byte() {
    let text = stiffid_core::io::text("group.csv", b"q1_deg,q2_deg".to_vec()).unwrap();
    assert_eq!(text, "q1_deg,q2_deg");
    let e = stiffid_core::io::text("bin.csv", vec![0xff, 0xfe]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "bin.csv: not UTF-8 text (invalid byte 0xFF at offset 0, line 1, column 1); Latin-1 or \
         Windows-1252 text, as some controllers write their files? convert it to UTF-8 (iconv -f \
         windows-1252 -t utf-8)"
    );
    let e = stiffid_core::io::text("p.src", b"DEF p( )\n; Z\xfcrich".to_vec()).unwrap_err();
    assert!(e
        .to_string()
        .contains("invalid byte 0xFC at offset 12, line 2, column 4"));
    let e = stiffid_core::io::text("b.bin", vec![b'a', 0x80]).unwrap_err();
    assert!(
        e.to_string().ends_with("line 1, column 2)"),
        "no Latin-1 letter: no hint"
    );
}
