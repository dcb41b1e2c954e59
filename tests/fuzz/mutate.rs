//! A structure-aware mutator of TOML documents, written for the fuzz harness (no fuzzing crate).
//!
//! A document is parsed into a [`toml::Table`]; a mutation picks a key path (`model.element[0].stiffness`)
//! and drops it, renames it (a typo), adds an unknown key beside it, replaces its value (hostile numbers,
//! `nan`/`inf`, random strings, quantities with the wrong or an unknown unit, empty arrays, values of the
//! wrong type), duplicates or removes an array element, or swaps two values. Raw mutations then work on the
//! serialised bytes (bit flips, inserted or deleted bytes, a duplicated line, truncation, deep nesting).
//!
//! Some mutations make a document that every correct reader must refuse (an unknown key, a wrong unit, a
//! non-finite number, a value of an impossible type): those carry [`Mutation::must_reject`], the finding
//! class to report if the library accepts the document anyway.

use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;
use serde::Serialize;
use stochvib::units::{parse_quantity, Dim};
use toml::{Table, Value};

/// The generator of the harness (the library's documented portable generator).
pub type Rng = Xoshiro256PlusPlus;

/// One step of a key path.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Seg {
    /// A key of a table.
    Key(String),
    /// An index of an array.
    Index(usize),
}

/// Dotted form of a path, as the library writes keys in its errors: `model.element[0].stiffness`.
pub fn path_str(p: &[Seg]) -> String {
    let mut s = String::new();
    for seg in p {
        match seg {
            Seg::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Seg::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// The path with every array index replaced by `[]` (for grouping findings).
pub fn normalize_path(p: &str) -> String {
    let mut out = String::new();
    let mut in_index = false;
    for c in p.chars() {
        match c {
            '[' => {
                in_index = true;
                out.push_str("[]");
            }
            ']' => in_index = false,
            _ if in_index => {}
            _ => out.push(c),
        }
    }
    out
}

/// Parses a dotted key as the library writes it (`a.b[0].c`, `band[1]`) into segments; keys are split at
/// `.` (the library never quotes keys).
pub fn parse_path(key: &str) -> Vec<Seg> {
    let mut segs = Vec::new();
    for part in key.split('.') {
        let mut rest = part;
        let name_end = rest.find('[').unwrap_or(rest.len());
        if name_end > 0 {
            segs.push(Seg::Key(rest[..name_end].to_string()));
        }
        rest = &rest[name_end..];
        while let Some(stripped) = rest.strip_prefix('[') {
            let Some(close) = stripped.find(']') else { break };
            match stripped[..close].parse::<usize>() {
                Ok(i) => segs.push(Seg::Index(i)),
                Err(_) => segs.push(Seg::Key(stripped[..close].to_string())),
            }
            rest = &stripped[close + 1..];
        }
    }
    segs
}

/// The value at `p`, if the path exists.
pub fn get<'a>(t: &'a Table, p: &[Seg]) -> Option<&'a Value> {
    let (first, rest) = p.split_first()?;
    let Seg::Key(k) = first else { return None };
    let mut v = t.get(k)?;
    for seg in rest {
        v = match (seg, v) {
            (Seg::Key(k), Value::Table(t)) => t.get(k)?,
            (Seg::Index(i), Value::Array(a)) => a.get(*i)?,
            _ => return None,
        };
    }
    Some(v)
}

fn get_mut<'a>(t: &'a mut Table, p: &[Seg]) -> Option<&'a mut Value> {
    let (first, rest) = p.split_first()?;
    let Seg::Key(k) = first else { return None };
    let mut v = t.get_mut(k)?;
    for seg in rest {
        v = match (seg, v) {
            (Seg::Key(k), Value::Table(t)) => t.get_mut(k)?,
            (Seg::Index(i), Value::Array(a)) => a.get_mut(*i)?,
            _ => return None,
        };
    }
    Some(v)
}

/// Every key path of the document, parents before children.
pub fn all_paths(t: &Table) -> Vec<Vec<Seg>> {
    fn walk(v: &Value, p: &mut Vec<Seg>, out: &mut Vec<Vec<Seg>>) {
        match v {
            Value::Table(t) => {
                for (k, x) in t {
                    p.push(Seg::Key(k.clone()));
                    out.push(p.clone());
                    walk(x, p, out);
                    p.pop();
                }
            }
            Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    p.push(Seg::Index(i));
                    out.push(p.clone());
                    walk(x, p, out);
                    p.pop();
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(&Value::Table(t.clone()), &mut Vec::new(), &mut out);
    out
}

/// Removes the value at `p` (a key of a table or an element of an array).
pub fn remove(t: &mut Table, p: &[Seg]) -> Option<Value> {
    let (last, parent) = p.split_last()?;
    let container: &mut Value = if parent.is_empty() {
        return match last {
            Seg::Key(k) => t.remove(k),
            Seg::Index(_) => None,
        };
    } else {
        get_mut(t, parent)?
    };
    match (last, container) {
        (Seg::Key(k), Value::Table(t)) => t.remove(k),
        (Seg::Index(i), Value::Array(a)) if *i < a.len() => Some(a.remove(*i)),
        _ => None,
    }
}

/// The table that holds `p` (the root for a top-level key), if `p` is a key of a table.
fn parent_table<'a>(t: &'a mut Table, p: &[Seg]) -> Option<&'a mut Table> {
    let (_, parent) = p.split_last()?;
    if parent.is_empty() {
        return Some(t);
    }
    get_mut(t, parent)?.as_table_mut()
}

/// What one mutation did.
#[derive(Debug, Clone, Serialize)]
pub struct Mutation {
    /// The operation: `drop`, `rename`, `add-key`, `replace:<class>`, `dup-element`, `remove-element`,
    /// `swap`, `inline-spectrum`.
    pub op: String,
    /// The key path it touched, as written in the library's errors.
    pub path: String,
    /// Human-readable detail (`-> 1e308`, `-> "5 kg"`, `-> alpah`).
    pub detail: String,
    /// If set, a correct reader must refuse the document; the value is the finding class otherwise.
    pub must_reject: Option<String>,
    /// The path and value that must still be in the final document for `must_reject` to hold (a later
    /// mutation may have removed it).
    #[serde(skip)]
    pub witness: Option<(Vec<Seg>, Value)>,
}

/// Every key name of the shipped files and of the library's readers that a typo must not collide with.
pub const EXTRA_KEYS: &[&str] = &[
    "name",
    "description",
    "source",
    "unit",
    "kind",
    "domain",
    "variance",
    "alpha",
    "beta",
    "class",
    "bound",
    "band",
    "unbounded",
    "form",
    "sigma_q",
    "numerator",
    "denominator",
    "convention",
    "level",
    "frequency_unit",
    "frequencies",
    "values",
    "g0",
    "n0",
    "waviness",
    "speed",
    "mean",
    "spectrum",
    "outputs",
    "duration",
    "levels",
    "title",
    "reference",
    "model",
    "input",
    "analysis",
    "gains",
    "positions",
    "delays",
    "delay",
];

/// Wrong-unit replacements with their dimension.
const OTHER_UNITS: &[&str] = &[
    "5 kg",
    "2 m/s",
    "1 Hz",
    "7 N",
    "4 s",
    "1 m^2",
    "3 m",
    "3 cycles/m",
    "2 kN/m",
    "0.5",
    "9 N*s/m",
    "3 kg m^2",
    "1 m/s^2",
    "6 N m",
];

/// Hostile numbers: (TOML value, description).
fn hostile_number(rng: &mut Rng) -> (Value, &'static str) {
    let choices: [(Value, &'static str); 20] = [
        (Value::Float(-1.0), "negative"),
        (Value::Integer(-3), "negative integer"),
        (Value::Float(0.0), "zero"),
        (Value::Float(-0.0), "negative zero"),
        (Value::Integer(0), "integer zero"),
        (Value::Float(1e308), "huge"),
        (Value::Float(-1e308), "huge negative"),
        (Value::Float(1e-308), "tiny"),
        (Value::Float(5e-324), "subnormal"),
        (Value::Float(f64::NAN), "nan"),
        (Value::Float(f64::INFINITY), "inf"),
        (Value::Float(f64::NEG_INFINITY), "-inf"),
        (Value::Integer(1 << 60), "2^60"),
        (Value::Integer(i64::MAX), "i64::MAX"),
        (Value::Integer(i64::MIN), "i64::MIN"),
        (Value::Integer((1 << 53) + 1), "2^53+1"),
        (Value::Integer(1 << 31), "2^31"),
        (Value::Float(1e15), "1e15"),
        (Value::Float(1e-15), "1e-15"),
        (Value::Integer(1), "one"),
    ];
    let (v, d) = &choices[rng.random_range(0..choices.len())];
    (v.clone(), d)
}

fn random_number(rng: &mut Rng) -> Value {
    if rng.random_bool(0.3) {
        Value::Integer(rng.random_range(-20..200))
    } else {
        let e: f64 = rng.random_range(-30.0..30.0);
        let s = if rng.random_bool(0.2) { -1.0 } else { 1.0 };
        Value::Float(s * 10f64.powf(e))
    }
}

const ALPHABET: &[u8] = b"abcdefghijklmnopqrstuvwxyzABCXYZ0123456789 _-./*^#\"'\\[]{}=,";

fn random_string(rng: &mut Rng) -> String {
    match rng.random_range(0..8) {
        0 => String::new(),
        1 => " \t ".into(),
        2 => ["μm", "∞", "Ω·m", "\u{202e}kg", "ｍ", "1e", "—", "\u{0}"][rng.random_range(0..8)].to_string(),
        3 => "x".repeat(rng.random_range(1000..20000)),
        4 => [
            "nan m", "inf Hz", "1e400 m", "-5 cm", "1e-400 s", "0x10 m", "1_000 kg", "+3 m", ".5 m", "5 m m",
        ][rng.random_range(0..10)]
        .to_string(),
        _ => {
            let n = rng.random_range(1..20);
            (0..n)
                .map(|_| ALPHABET[rng.random_range(0..ALPHABET.len())] as char)
                .collect()
        }
    }
}

/// A key name that is none of `vocabulary` (a typo of `key`, or a fresh word).
fn typo(rng: &mut Rng, key: &str, vocabulary: &[String]) -> Option<String> {
    for _ in 0..20 {
        let mut c: Vec<char> = key.chars().collect();
        let t = match rng.random_range(0..7) {
            0 if c.len() >= 2 => {
                let i = rng.random_range(0..c.len() - 1);
                c.swap(i, i + 1);
                c.into_iter().collect()
            }
            1 if c.len() >= 2 => {
                c.remove(rng.random_range(0..c.len()));
                c.into_iter().collect()
            }
            2 if !c.is_empty() => {
                let i = rng.random_range(0..c.len());
                c.insert(i, c[i]);
                c.into_iter().collect()
            }
            3 if !c.is_empty() => {
                let i = rng.random_range(0..c.len());
                c[i] = if c[i].is_uppercase() {
                    c[i].to_ascii_lowercase()
                } else {
                    c[i].to_ascii_uppercase()
                };
                c.into_iter().collect()
            }
            4 => key.replace('_', "-"),
            5 => format!("{key}s"),
            _ => format!("zz_{}", rng.random_range(0..1000)),
        };
        if !t.is_empty() && t != key && !vocabulary.contains(&t) {
            return Some(t);
        }
    }
    None
}

/// The dimension of a quantity string with a unit (`"3.5 cm"`), if it is one.
fn quantity_dim(v: &Value) -> Option<(Dim, String)> {
    let s = v.as_str()?;
    let (num, unit) = s.trim().split_once(char::is_whitespace)?;
    let (_, d) = parse_quantity(s).ok()?;
    num.parse::<f64>().ok()?;
    Some((d, unit.trim().to_string()))
}

fn is_numeric(v: &Value) -> bool {
    matches!(v, Value::Integer(_) | Value::Float(_))
}

/// True for a value that is free text of a reference file or a description, never read as a quantity:
/// everything under `printed_parameters` and `not_printed`, and `printed_symbol`, `status`, `source`,
/// `title`, `description` and `name` anywhere (a name is a label: a workday task called `"3 furlong"` or
/// `"nan m"` is a strange name, not a quantity with an unknown unit or a non-finite number).
pub fn free_text(p: &[Seg]) -> bool {
    let keys: Vec<&str> = p
        .iter()
        .filter_map(|s| match s {
            Seg::Key(k) => Some(k.as_str()),
            _ => None,
        })
        .collect();
    matches!(keys.first(), Some(&"printed_parameters") | Some(&"not_printed"))
        || matches!(
            keys.last(),
            Some(&"printed_symbol")
                | Some(&"status")
                | Some(&"source")
                | Some(&"title")
                | Some(&"description")
                | Some(&"name")
        )
}

/// A replacement value for `old`: (value, class of the replacement, must_reject class).
pub fn replacement(rng: &mut Rng, old: &Value) -> (Value, String, Option<String>) {
    let qd = quantity_dim(old);
    let numeric_like = is_numeric(old) || qd.is_some();
    // Integers are counts, indices and sizes (`base_inputs`, `point = [1, 0]`, dB levels): often huge or
    // negative ones.
    if matches!(old, Value::Integer(_)) && rng.random_bool(0.4) {
        let (v, d) = [
            (1i64 << 60, "2^60"),
            (i64::MAX, "i64::MAX"),
            (i64::MIN, "i64::MIN"),
            (-1, "-1"),
            (0, "0"),
            (1 << 31, "2^31"),
            (1 << 32, "2^32"),
            ((1 << 53) + 1, "2^53+1"),
            (1_000_000, "1e6"),
            (100_000_000, "1e8"),
        ][rng.random_range(0..10)];
        return (Value::Integer(v), format!("integer:{d}"), None);
    }
    // Half of the replacements of a number keep it plausible (the original scaled by 10^±3, sometimes
    // negated), so that many cases get past validation and exercise the numerics.
    if numeric_like && rng.random_bool(0.5) {
        let f = 10f64.powf(rng.random_range(-3.0..3.0)) * if rng.random_bool(0.1) { -1.0 } else { 1.0 };
        let v = match (old, &qd) {
            (Value::Integer(i), _) if rng.random_bool(0.5) => Value::Integer(((*i as f64) * f).round() as i64),
            (Value::Integer(i), _) => Value::Float(*i as f64 * f),
            (Value::Float(x), _) => Value::Float(x * f),
            (Value::String(s), Some((_, unit))) => {
                let num: f64 = s.split_whitespace().next().and_then(|n| n.parse().ok()).unwrap_or(1.0);
                Value::String(format!("{:e} {unit}", num * f))
            }
            _ => old.clone(),
        };
        return (v, "scaled".into(), None);
    }
    match rng.random_range(0..12) {
        0 | 1 => {
            let (v, d) = hostile_number(rng);
            let nonfinite = matches!(v, Value::Float(x) if !x.is_finite());
            let must = (nonfinite && numeric_like).then(|| "non-finite-accepted".to_string());
            (v, format!("number:{d}"), must)
        }
        2 => (random_number(rng), "number:random".into(), None),
        3 => (Value::String(random_string(rng)), "string".into(), None),
        4 | 5 => {
            // wrong or unknown unit
            if rng.random_bool(0.3) {
                let must = numeric_like.then(|| "unknown-unit-accepted".to_string());
                (Value::String("3 furlong".into()), "unit:unknown".into(), must)
            } else {
                let own = qd.as_ref().map(|(d, _)| *d);
                let cands: Vec<&&str> = OTHER_UNITS
                    .iter()
                    .filter(|u| parse_quantity(u).map(|(_, d)| Some(d) != own).unwrap_or(false))
                    .collect();
                let u = cands[rng.random_range(0..cands.len())];
                // Only a quantity string of known dimension says which dimension is right.
                let must = qd.is_some().then(|| "wrong-unit-accepted".to_string());
                (Value::String(u.to_string()), "unit:wrong-dimension".into(), must)
            }
        }
        6 => {
            // right unit, hostile magnitude
            match &qd {
                Some((_, unit)) => {
                    let (num, must) = [
                        ("1e308", None),
                        ("-1e308", None),
                        ("-5", None),
                        ("0", None),
                        ("1e-320", None),
                        ("nan", Some("non-finite-accepted")),
                        ("inf", Some("non-finite-accepted")),
                        ("1e400", Some("non-finite-accepted")),
                        ("1152921504606846976", None),
                    ][rng.random_range(0..9)];
                    (
                        Value::String(format!("{num} {unit}")),
                        "quantity:hostile".into(),
                        must.map(str::to_string),
                    )
                }
                None => (random_number(rng), "number:random".into(), None),
            }
        }
        7 => (Value::Array(vec![]), "empty-array".into(), None),
        8 => {
            // a value of a type no key of these files accepts
            let (v, d) = match rng.random_range(0..4) {
                0 => (Value::Boolean(true), "bool"),
                1 => (
                    Value::Datetime("1979-05-27T07:32:00Z".parse().expect("a valid TOML datetime")),
                    "datetime",
                ),
                2 => {
                    let mut t = Table::new();
                    t.insert("zz_unknown".into(), Value::Integer(1));
                    (Value::Table(t), "table")
                }
                _ => (Value::Array(vec![Value::Boolean(false)]), "array-of-bool"),
            };
            // never valid anywhere in these files (a table with an unknown key, `[false]`, a datetime), except
            // a boolean where a boolean was
            let must = !(old.is_bool() && v.is_bool());
            let must = must.then(|| "wrong-type-accepted".to_string());
            (v, format!("type:{d}"), must)
        }
        9 => {
            let n = if rng.random_bool(0.1) {
                rng.random_range(1000..20000)
            } else {
                rng.random_range(1..6)
            };
            (
                Value::Array((0..n).map(|_| random_number(rng)).collect()),
                "array:numbers".into(),
                None,
            )
        }
        10 => {
            let n = rng.random_range(1..4);
            (
                Value::Array((0..n).map(|_| Value::String(random_string(rng))).collect()),
                "array:strings".into(),
                None,
            )
        }
        _ => {
            // integers as text types and the other way round
            match old {
                Value::String(_) => (Value::Integer(rng.random_range(-5..5)), "type:integer".into(), None),
                _ => (Value::String(random_string(rng)), "string".into(), None),
            }
        }
    }
}

/// Applies one random structured mutation to `doc`.
pub fn mutate_once(rng: &mut Rng, doc: &mut Table, vocabulary: &[String]) -> Option<Mutation> {
    let paths = all_paths(doc);
    if paths.is_empty() {
        return None;
    }
    // 70 % of the mutations hit a leaf value (numbers, strings), the rest any key including tables
    let leaves: Vec<&Vec<Seg>> = paths
        .iter()
        .filter(|q| !matches!(get(doc, q), Some(Value::Table(_)) | Some(Value::Array(_))))
        .collect();
    let p = if !leaves.is_empty() && rng.random_bool(0.7) {
        leaves[rng.random_range(0..leaves.len())].clone()
    } else {
        paths[rng.random_range(0..paths.len())].clone()
    };
    let old = get(doc, &p)?.clone();
    let ps = path_str(&p);
    let mut m = Mutation {
        op: String::new(),
        path: ps.clone(),
        detail: String::new(),
        must_reject: None,
        witness: None,
    };
    match rng.random_range(0..14) {
        0 | 1 => {
            remove(doc, &p)?;
            m.op = "drop".into();
        }
        2 => {
            let Some(Seg::Key(k)) = p.last() else { return None };
            let new = typo(rng, k, vocabulary)?;
            let parent = parent_table(doc, &p)?;
            let v = parent.remove(k)?;
            parent.insert(new.clone(), v.clone());
            let mut wp = p.clone();
            *wp.last_mut()? = Seg::Key(new.clone());
            m.op = "rename".into();
            m.detail = format!("-> {new}");
            m.must_reject = Some("typo-accepted".into());
            m.witness = Some((wp, v));
        }
        3 => {
            // an unknown key beside p (in p's table)
            let Some(Seg::Key(k)) = p.last() else { return None };
            let new = typo(rng, k, vocabulary)?;
            let v = random_number(rng);
            parent_table(doc, &p)?.insert(new.clone(), v.clone());
            let mut wp = p.clone();
            *wp.last_mut()? = Seg::Key(new.clone());
            m.op = "add-key".into();
            m.detail = format!("+ {new} = {v}");
            m.must_reject = Some("unknown-key-accepted".into());
            m.witness = Some((wp, v));
        }
        4..=10 => {
            let (v, class, must) = replacement(rng, &old);
            // a transcription of printed text (Table 8.1's `printed_parameters`, `printed_symbol`, titles and
            // sources) holds what the print says, e.g. "17...20 1/s": no reader takes it as a quantity, so
            // any replacement of it is acceptable
            let must = if free_text(&p) { None } else { must };
            let shown = short(&v.to_string());
            *get_mut(doc, &p)? = v.clone();
            m.op = format!("replace:{class}");
            m.detail = format!("{} -> {shown}", short(&old.to_string()));
            m.must_reject = must;
            m.witness = Some((p.clone(), v));
        }
        11 => {
            // duplicate an array element (or the value itself into a one-element array's neighbour)
            let Value::Array(a) = get_mut(doc, &p)? else {
                // not an array: duplicate the enclosing array element if p is inside one
                let i = p.iter().rposition(|s| matches!(s, Seg::Index(_)))?;
                let arr_path = &p[..i];
                let Value::Array(a) = get_mut(doc, arr_path)? else {
                    return None;
                };
                let Seg::Index(j) = p[i] else { return None };
                let e = a.get(j)?.clone();
                a.insert(j + 1, e);
                m.op = "dup-element".into();
                m.path = path_str(&p[..=i]);
                return Some(m);
            };
            if a.is_empty() {
                return None;
            }
            let j = rng.random_range(0..a.len());
            let e = a[j].clone();
            a.insert(j + 1, e);
            m.op = "dup-element".into();
            m.path = format!("{ps}[{j}]");
        }
        12 => {
            let Value::Array(a) = get_mut(doc, &p)? else {
                return None;
            };
            if a.is_empty() {
                return None;
            }
            let j = rng.random_range(0..a.len());
            a.remove(j);
            m.op = "remove-element".into();
            m.path = format!("{ps}[{j}]");
        }
        _ => {
            // swap with another leaf's value
            let leaves: Vec<&Vec<Seg>> = paths
                .iter()
                .filter(|q| !matches!(get(doc, q), Some(Value::Table(_)) | Some(Value::Array(_))) && **q != p)
                .collect();
            if leaves.is_empty() {
                return None;
            }
            let q = leaves[rng.random_range(0..leaves.len())].clone();
            if q.starts_with(&p) || p.starts_with(&q) {
                return None;
            }
            let qv = get(doc, &q)?.clone();
            *get_mut(doc, &p)? = qv;
            *get_mut(doc, &q)? = old;
            m.op = "swap".into();
            m.detail = format!("<-> {}", path_str(&q));
        }
    }
    Some(m)
}

/// Shortens a value's text for descriptions.
pub fn short(s: &str) -> String {
    short_to(s, 60)
}

/// Shortens `s` to about `n` characters.
pub fn short_to(s: &str, n: usize) -> String {
    if s.chars().count() > n {
        format!(
            "{}…({} chars)",
            s.chars().take(n * 2 / 3).collect::<String>(),
            s.chars().count()
        )
    } else {
        s.to_string()
    }
}

/// Applies one raw mutation to the serialised text; returns its description.
pub fn mutate_bytes(rng: &mut Rng, bytes: &mut Vec<u8>) -> String {
    if bytes.is_empty() {
        bytes.extend_from_slice(b"x");
    }
    match rng.random_range(0..9) {
        0 | 1 => {
            let n = rng.random_range(1..5);
            let mut at = Vec::new();
            for _ in 0..n {
                let i = rng.random_range(0..bytes.len());
                let b = rng.random_range(0..8);
                bytes[i] ^= 1 << b;
                at.push(format!("{i}:{b}"));
            }
            format!("bit flips at byte:bit {}", at.join(" "))
        }
        2 => {
            let special: &[u8] = b"\0\"[]={}#\n\\,\x7f\xff\xc3.'";
            let i = rng.random_range(0..=bytes.len());
            let b = special[rng.random_range(0..special.len())];
            bytes.insert(i, b);
            format!("inserted byte {b:#04x} at {i}")
        }
        3 => {
            let i = rng.random_range(0..bytes.len());
            let n = rng.random_range(1..=(bytes.len() - i).min(40));
            bytes.drain(i..i + n);
            format!("deleted {n} bytes at {i}")
        }
        4 => {
            // duplicate a line
            let text = String::from_utf8_lossy(bytes).into_owned();
            let lines: Vec<&str> = text.split('\n').collect();
            let i = rng.random_range(0..lines.len());
            let mut out: Vec<&str> = lines.clone();
            out.insert(i, lines[i]);
            *bytes = out.join("\n").into_bytes();
            format!("duplicated line {}: {}", i + 1, short(lines[i]))
        }
        5 => {
            let n = rng.random_range(0..bytes.len());
            bytes.truncate(n);
            format!("truncated to {n} bytes")
        }
        6 => {
            let depth = [64usize, 1_000, 100_000][rng.random_range(0..3)];
            let (open, close) = if rng.random_bool(0.5) { ("[", "]") } else { ("{a=", "}") };
            let blob = format!("zz_deep = {}1{}\n", open.repeat(depth), close.repeat(depth));
            let mut b = blob.into_bytes();
            b.extend_from_slice(bytes);
            *bytes = b;
            format!("prepended a value nested {depth} deep with {open}")
        }
        7 => {
            bytes.splice(0..0, [0xef, 0xbb, 0xbf]);
            "prepended a UTF-8 byte-order mark".into()
        }
        _ => {
            let text = String::from_utf8_lossy(bytes).replace('\n', "\r\n");
            *bytes = text.into_bytes();
            "line ends to CRLF".into()
        }
    }
}

/// Whether the expectation of mutation `i` still says something: a `wrong-unit-accepted` judgment is
/// relative to the value the mutation replaced, so it holds only when that value was the shipped one — not
/// when an earlier mutation of the case had set the same key or a table around it (a band edge `"3 kg m^2"`
/// set by one mutation and replaced by `"1 Hz"` by the next is right, not wrong).
pub fn expectation_holds(mutations: &[Mutation], i: usize) -> bool {
    let m = &mutations[i];
    if m.must_reject.as_deref() != Some("wrong-unit-accepted") {
        return true;
    }
    let at = |m: &Mutation| match &m.witness {
        Some((p, _)) => path_str(p),
        None => m.path.clone(),
    };
    let here = at(m);
    !mutations[..i].iter().any(|e| {
        let there = at(e);
        here.strip_prefix(&there)
            .is_some_and(|rest| rest.is_empty() || rest.starts_with('.') || rest.starts_with('['))
    })
}
