//! Nonlinear-section cases: a scenario with `[[model.nonlinear]]` elements (a shipped one, or a quarter car
//! given one element of every kind in turn) whose element tables are mutated by the TOML mutator — the
//! kinds' keys, `across`, `point`, `to` — and evaluated as `stochvib analyze` evaluates them (routes 1 and
//! 3, the report). The invariants are those of the TOML cases ([`super::inputs`]).

use super::inputs::Corpus;
use super::mutate::{self, Mutation, Rng, Seg};
use rand::RngExt;
use toml::{Table, Value};

/// One element of every kind, placed on a quarter car (`across` its suspension or tyre, or by `point` and
/// `to`), with the values of the shipped scenarios' order of magnitude.
const ELEMENTS: &[&str] = &[
    r#"kind = "bump-stop"
across = "suspension"
upper_clearance = "5 cm"
stiffness = "200 kN/m""#,
    r#"kind = "bump-stop"
point = [1, -1]
to = "ground"
lower_clearance = "3 cm"
lower_stiffness = "100 kN/m""#,
    r#"kind = "cubic-spring"
across = "suspension"
cubic_stiffness = "1e7 N/m^3""#,
    r#"kind = "quadratic-damper"
across = "suspension"
coefficient = "500 N*s^2/m^2""#,
    r#"kind = "coulomb-friction"
across = "suspension"
force = "100 N""#,
    r#"kind = "tyre-contact"
across = "tyre"
static_load = "3335.4 N""#,
    r#"kind = "bilinear-damper"
point = [0, 1]
to = "base 0"
rebound_damping = "2 kN*s/m"
compression_damping = "1 kN*s/m""#,
];

/// The scenarios of `data/` with nonlinear elements, and the quarter cars (which take any element).
fn origins(corpus: &Corpus) -> Vec<(&str, &Table)> {
    corpus
        .seeds
        .iter()
        .filter(|s| {
            let model = s.table.get("model").and_then(Value::as_table);
            model.is_some_and(|m| {
                m.contains_key("nonlinear") || m.get("kind").and_then(Value::as_str) == Some("quarter-car")
            })
        })
        .map(|s| (s.rel.as_str(), &s.table))
        .collect()
}

/// A nonlinear scenario (origin, document, mutations): 0–1 elements added, then 1–3 mutations of the
/// element tables (paths `model.nonlinear…`); `None` when the corpus has no such scenario.
pub fn mutated(corpus: &Corpus, rng: &mut Rng) -> Option<(String, Table, Vec<Mutation>)> {
    let all = origins(corpus);
    if all.is_empty() {
        return None;
    }
    let (rel, table) = all[rng.random_range(0..all.len())];
    let mut doc = table.clone();
    let model = doc.get_mut("model")?.as_table_mut()?;
    let mut mutations = Vec::new();
    if !model.contains_key("nonlinear") || rng.random_bool(0.4) {
        let text = ELEMENTS[rng.random_range(0..ELEMENTS.len())];
        let element: Table = text.parse().expect("a template element");
        let list = model.entry("nonlinear").or_insert_with(|| Value::Array(Vec::new()));
        list.as_array_mut()?.push(Value::Table(element));
        mutations.push(Mutation {
            op: "add-element".into(),
            path: "model.nonlinear".into(),
            detail: text.lines().next().unwrap_or("").to_string(),
            must_reject: None,
            witness: None,
        });
    }
    // the element tables alone, so that every mutation lands in them
    let mut part = Table::new();
    part.insert("nonlinear".into(), model.remove("nonlinear")?);
    let (n, mut done) = (rng.random_range(1..4), 0);
    for _ in 0..n * 5 {
        if done == n {
            break;
        }
        if let Some(m) = mutate::mutate_once(rng, &mut part, &corpus.vocabulary) {
            mutations.push(within_model(m));
            done += 1;
        }
    }
    // back into [model], under whatever name a mutation gave it
    model.extend(part);
    Some((rel.to_string(), doc, mutations))
}

/// A mutation of the `nonlinear` part re-rooted at `model`.
fn within_model(mut m: Mutation) -> Mutation {
    m.path = format!("model.{}", m.path);
    if let Some((p, _)) = &mut m.witness {
        p.insert(0, Seg::Key("model".into()));
    }
    m
}
