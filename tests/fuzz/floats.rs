//! Finds every non-finite `f64` in a serialisable value, with its path.
//!
//! `serde_json` writes NaN and ±∞ as `null`, the same as a `None`, so a report's JSON cannot tell "no value
//! (with a reason elsewhere)" from "a NaN printed as a result". This module walks the value through serde
//! itself (a minimal [`serde::Serializer`] that only looks at numbers) and records the dotted path of each
//! non-finite float, e.g. `outputs[0].statistics.sigma`.

use serde::ser::{self, Serialize};
use std::fmt;

/// The paths and values of every non-finite `f64`/`f32` inside `value`.
pub fn non_finite<T: Serialize + ?Sized>(value: &T) -> Vec<(String, f64)> {
    let mut s = Scan::default();
    // The scanner itself never fails; a custom error from a `Serialize` impl is recorded as a finding.
    if let Err(e) = value.serialize(&mut s) {
        s.found.push((format!("<serialize error: {e}>"), f64::NAN));
    }
    s.found
}

#[derive(Default)]
struct Scan {
    path: Vec<String>,
    found: Vec<(String, f64)>,
}

impl Scan {
    fn here(&self) -> String {
        let mut p = String::new();
        for seg in &self.path {
            if !seg.starts_with('[') && !p.is_empty() {
                p.push('.');
            }
            p.push_str(seg);
        }
        p
    }

    fn float(&mut self, v: f64) {
        if !v.is_finite() {
            let p = self.here();
            self.found.push((p, v));
        }
    }

    fn nested<T: Serialize + ?Sized>(&mut self, seg: String, v: &T) -> Result<(), ScanError> {
        self.path.push(seg);
        let r = v.serialize(&mut *self);
        self.path.pop();
        r
    }
}

/// The error type the trait requires (only produced by `Serialize` impls that fail on purpose).
#[derive(Debug)]
pub struct ScanError(String);

impl fmt::Display for ScanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ScanError {}

impl ser::Error for ScanError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        ScanError(msg.to_string())
    }
}

/// Sequence-like compounds: elements get `[i]`.
struct Seq<'a> {
    scan: &'a mut Scan,
    index: usize,
}

/// Struct-like compounds: fields get their name.
struct Fields<'a> {
    scan: &'a mut Scan,
}

/// Maps: the value gets its key as written by `serde_json`.
struct Map<'a> {
    scan: &'a mut Scan,
    key: String,
}

impl<'a> Seq<'a> {
    fn element<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), ScanError> {
        let seg = format!("[{}]", self.index);
        self.index += 1;
        self.scan.nested(seg, v)
    }
}

macro_rules! seq_impl {
    ($trait:ident, $method:ident) => {
        impl<'a> ser::$trait for Seq<'a> {
            type Ok = ();
            type Error = ScanError;
            fn $method<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), ScanError> {
                self.element(v)
            }
            fn end(self) -> Result<(), ScanError> {
                Ok(())
            }
        }
    };
}
seq_impl!(SerializeSeq, serialize_element);
seq_impl!(SerializeTuple, serialize_element);
seq_impl!(SerializeTupleStruct, serialize_field);
seq_impl!(SerializeTupleVariant, serialize_field);

macro_rules! fields_impl {
    ($trait:ident) => {
        impl<'a> ser::$trait for Fields<'a> {
            type Ok = ();
            type Error = ScanError;
            fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, v: &T) -> Result<(), ScanError> {
                self.scan.nested(key.to_string(), v)
            }
            fn end(self) -> Result<(), ScanError> {
                Ok(())
            }
        }
    };
}
fields_impl!(SerializeStruct);
fields_impl!(SerializeStructVariant);

impl<'a> ser::SerializeMap for Map<'a> {
    type Ok = ();
    type Error = ScanError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), ScanError> {
        self.key = serde_json::to_string(key).unwrap_or_else(|_| "<key>".into());
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), ScanError> {
        let seg = std::mem::take(&mut self.key);
        self.scan.nested(seg, v)
    }
    fn end(self) -> Result<(), ScanError> {
        Ok(())
    }
}

impl<'a> ser::Serializer for &'a mut Scan {
    type Ok = ();
    type Error = ScanError;
    type SerializeSeq = Seq<'a>;
    type SerializeTuple = Seq<'a>;
    type SerializeTupleStruct = Seq<'a>;
    type SerializeTupleVariant = Seq<'a>;
    type SerializeMap = Map<'a>;
    type SerializeStruct = Fields<'a>;
    type SerializeStructVariant = Fields<'a>;

    fn serialize_f64(self, v: f64) -> Result<(), ScanError> {
        self.float(v);
        Ok(())
    }
    fn serialize_f32(self, v: f32) -> Result<(), ScanError> {
        self.float(f64::from(v));
        Ok(())
    }
    fn serialize_bool(self, _: bool) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_i8(self, _: i8) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_i16(self, _: i16) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_i32(self, _: i32) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_i64(self, _: i64) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_u8(self, _: u8) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_u16(self, _: u16) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_u32(self, _: u32) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_u64(self, _: u64) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_char(self, _: char) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_str(self, _: &str) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_bytes(self, _: &[u8]) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_none(self) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> Result<(), ScanError> {
        v.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Result<(), ScanError> {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> Result<(), ScanError> {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        v: &T,
    ) -> Result<(), ScanError> {
        self.nested(variant.to_string(), v)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Seq<'a>, ScanError> {
        Ok(Seq { scan: self, index: 0 })
    }
    fn serialize_tuple(self, _: usize) -> Result<Seq<'a>, ScanError> {
        Ok(Seq { scan: self, index: 0 })
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Seq<'a>, ScanError> {
        Ok(Seq { scan: self, index: 0 })
    }
    fn serialize_tuple_variant(self, _: &'static str, _: u32, _: &'static str, _: usize) -> Result<Seq<'a>, ScanError> {
        Ok(Seq { scan: self, index: 0 })
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Map<'a>, ScanError> {
        Ok(Map {
            scan: self,
            key: String::new(),
        })
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Fields<'a>, ScanError> {
        Ok(Fields { scan: self })
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Fields<'a>, ScanError> {
        Ok(Fields { scan: self })
    }
}
