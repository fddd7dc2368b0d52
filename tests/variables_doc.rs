//! `docs/variables.md` is what the variable table makes of it (`trb::variables_doc`): a
//! change of a variable's name, unit, range or description shows in the docs. With
//! `TRB_BLESS=1` the test writes the file instead.

#[test]
fn the_variable_reference_is_generated_from_the_variable_table() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/variables.md");
    let generated = trb::variables_doc::markdown();
    if std::env::var("TRB_BLESS").is_ok_and(|v| v == "1") {
        std::fs::write(path, &generated).unwrap();
    }
    let on_disk = std::fs::read_to_string(path).unwrap_or_default();
    assert!(
        on_disk == generated,
        "docs/variables.md is not what the variable table makes: regenerate it with TRB_BLESS=1 cargo test --release --test variables_doc"
    );
    // every variable is there, once
    for v in trb::variables::TABLE {
        let name = format!("| `{}` |", v.name.replace("{j}", "j"));
        assert_eq!(generated.matches(&name).count(), 1, "{name}");
    }
}
