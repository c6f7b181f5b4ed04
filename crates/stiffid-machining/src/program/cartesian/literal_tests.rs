//! RAPID's nested literals (`crate::program::cartesian::literal`).

use crate::program::cartesian::literal::*;

#[test]
fn nested_literals_keep_every_numbers_span() {
    let code = "x := [TRUE,[[1.5, -2,3e2],[1,0,0,0]],\"a\"];";
    let (node, end) = parse(code, 4).unwrap();
    assert_eq!(&code[end..], ";");
    let items = node.list().unwrap();
    assert_eq!(items[0].boolean(), Some(true));
    let p = items[1].list().unwrap()[0].numbers(3).unwrap();
    assert_eq!(p[2].0, 300.0);
    assert_eq!(&code[p[1].1.clone()], "-2");
    assert_eq!(items[2], Node::Text("a".into()));
    assert!(parse("[1,2", 0).is_none());
    assert!(parse("[1;2]", 0).is_none());
}

#[test]
fn a_literal_nested_deeper_than_the_data_types_is_none_without_exhausting_the_stack() {
    let nested = |n: usize| format!("{}1{}", "[".repeat(n), "]".repeat(n));
    let (node, end) = parse(&nested(MAX_DEPTH), 0).unwrap();
    assert_eq!(end, 2 * MAX_DEPTH + 1);
    let mut inner = &node;
    for _ in 1..MAX_DEPTH {
        inner = &inner.list().unwrap()[0];
    }
    assert_eq!(inner.numbers(1).unwrap()[0].0, 1.0);
    assert!(parse(&nested(MAX_DEPTH + 1), 0).is_none());
    // A million brackets, read recursively, overflowed the stack and aborted the process.
    assert!(parse(&nested(1_000_000), 0).is_none());
}
