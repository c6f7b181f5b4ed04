#[test]
fn csv_text_quotes_only_the_fields_that_need_it_and_reads_back() {
    let header = ["name".to_string(), "checks".to_string()];
    let rows = [
        vec!["a,b".to_string(), "floor; \"rope\" blocked".to_string()],
        vec!["plain".to_string(), String::new()],
    ];
    let text = stiffid::app::document::csv_text(&header, rows.clone());
    assert_eq!(
        text,
        "name,checks\n\"a,b\",\"floor; \"\"rope\"\" blocked\"\nplain,\n"
    );
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let back: Vec<Vec<String>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(String::from).collect())
        .collect();
    assert_eq!(back, rows);
}
