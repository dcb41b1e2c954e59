//! The `book` report: every worked example is present, every difference over 2 % is explained, and the
//! computed values are the independent derivations (checked in the models' own test files).

use stochvib::models::worked_example::EXPLAIN_ABOVE;
use stochvib::report::book::BookReport;

fn book_report() -> BookReport {
    BookReport {
        rows: stochvib::models::worked_example::book_rows(),
    }
}

#[test]
fn every_large_difference_is_explained() {
    let r = book_report();
    let bad: Vec<String> = r
        .unexplained()
        .iter()
        .map(|row| format!("{} / {}", row.example, row.quantity))
        .collect();
    assert!(bad.is_empty(), "rows over {EXPLAIN_ABOVE} without explanation: {bad:?}");
}

/// Every worked example named in the issue contributes rows.
#[test]
fn every_worked_example_is_reported() {
    let r = book_report();
    for needle in [
        "8.5",
        "Example 8.1",
        "Table 8.1",
        "Example 7.1",
        "xcavator",
        "Example 7.2",
        "Ofiy & Rakhmaniy (2010)",
        "Yurchenko (2011)",
        "Dvornikov, Kondrakhin & Velebnik (2014)",
    ] {
        assert!(
            r.rows.iter().any(|row| row.example.contains(needle)),
            "no rows for {needle}"
        );
    }
    // no computed value is NaN; missing values are None with an explanation
    for row in &r.rows {
        if let Some(c) = row.computed {
            assert!(c.is_finite(), "{} / {}", row.example, row.quantity);
        } else {
            assert!(!row.explanation.is_empty(), "{} / {}", row.example, row.quantity);
        }
    }
}
