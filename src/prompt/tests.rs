//! Unit tests of the reader: counts, relations, negation, attributes, house splitting.

use super::*;

fn find<'a>(r: &'a Reading, cat: &str) -> &'a Mention {
    r.mentions
        .iter()
        .find(|m| m.category == cat)
        .unwrap_or_else(|| {
            panic!(
                "no {cat} in {:#?}",
                r.mentions.iter().map(|m| &m.category).collect::<Vec<_>>()
            )
        })
}

#[test]
fn counts_and_room_type() {
    let r = read("A small kitchen with a table, four chairs and at least 10 mugs.");
    assert_eq!(r.room_type, "kitchen");
    assert_eq!(r.size_scale, 0.8);
    assert_eq!(find(&r, "table").count, Count::Exactly(1));
    assert_eq!(find(&r, "chair").count, Count::Exactly(4));
    assert_eq!(find(&r, "mug").count, Count::AtLeast(10));
}
