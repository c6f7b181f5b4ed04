use super::backup::Backup;
use stiffid_core::Error;

/// A file is found by its file name, case aside, whatever folder it came from; two files of
/// one name are refused naming both.
#[test]
fn files_are_found_by_name_and_two_of_one_name_refused() {
    let files = vec![
        ("backup/SYSFRAME.VA".to_string(), "a".to_string()),
        ("C:\\md\\posreg.va".to_string(), "b".to_string()),
    ];
    let backup = Backup::new(files).unwrap();
    assert_eq!(backup.file("sysframe.va").unwrap().text, "a");
    assert_eq!(backup.file("POSREG.VA").unwrap().name, "C:\\md\\posreg.va");
    assert!(backup.file("TOOL.CND").is_none());
    let twice = vec![
        ("a/TOOL.CND".to_string(), String::new()),
        ("b/tool.cnd".to_string(), String::new()),
    ];
    match Backup::new(twice) {
        Err(Error::InvalidField { field, message }) => {
            assert_eq!(field, "backup");
            assert!(
                message.starts_with("a/TOOL.CND and b/tool.cnd"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}
