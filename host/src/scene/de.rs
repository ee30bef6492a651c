//! A serde deserializer over a parsed TOML value that names the key of an error.
//!
//! `toml`'s own `Table::try_into` reports "invalid type: string \"abc\", expected f64" without
//! saying where. This deserializer records the path on the way back up (`materials[0].rho0`),
//! and words unknown and missing keys as `KEY: unknown key (known: ...)` and `KEY: missing`.

use crate::output::safe::{excerpt, shorten_quotes};
use serde::de::{self, DeserializeSeed, IntoDeserializer, MapAccess, SeqAccess, Visitor};
use std::fmt;

/// One step of a key path.
#[derive(Debug, Clone)]
enum Seg {
    Key(String),
    Index(usize),
}

/// A deserialization error with the key path it happened at.
#[derive(Debug, Clone)]
pub struct PathError {
    /// Innermost first (segments are pushed while the error travels up).
    rev_path: Vec<Seg>,
    msg: String,
}

impl PathError {
    fn within(mut self, seg: Seg) -> Self {
        self.rev_path.push(seg);
        self
    }

    /// The key path, e.g. `bodies[1].shape.max` (empty at the top level).
    pub fn key(&self) -> String {
        let mut s = String::new();
        for seg in self.rev_path.iter().rev() {
            match seg {
                // a key is text of the file: quoted as an excerpt
                Seg::Key(k) if s.is_empty() => s.push_str(&excerpt(k)),
                Seg::Key(k) => {
                    s.push('.');
                    s.push_str(&excerpt(k));
                }
                Seg::Index(i) => s.push_str(&format!("[{i}]")),
            }
        }
        s
    }
}

impl fmt::Display for PathError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let key = self.key();
        // serde quotes a wrong value whole (`invalid type: string "..."`): the value is
        // text of the file, quoted as an excerpt
        let msg = shorten_quotes(&self.msg.replace('\n', " "));
        if key.is_empty() {
            f.write_str(&msg)
        } else {
            write!(f, "{key}: {msg}")
        }
    }
}

impl std::error::Error for PathError {}

impl de::Error for PathError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        PathError {
            rev_path: Vec::new(),
            msg: msg.to_string(),
        }
    }

    fn missing_field(field: &'static str) -> Self {
        PathError {
            rev_path: vec![Seg::Key(field.into())],
            msg: "missing (this key is required)".into(),
        }
    }

    fn unknown_field(field: &str, expected: &'static [&'static str]) -> Self {
        let msg = if expected.is_empty() {
            "unknown key (this table takes no other keys)".to_string()
        } else {
            format!("unknown key (known: {})", expected.join(", "))
        };
        PathError {
            rev_path: vec![Seg::Key(field.into())],
            msg,
        }
    }

    fn unknown_variant(variant: &str, expected: &'static [&'static str]) -> Self {
        de::Error::custom(format!(
            "unknown type `{variant}` (known: {})",
            expected.join(", ")
        ))
    }
}

/// Deserializes `T` from a TOML table, naming the key of any error.
pub fn from_table<T: de::DeserializeOwned>(t: toml::Table) -> Result<T, PathError> {
    let root = toml::Value::Table(t);
    T::deserialize(ValueDe(root.clone())).map_err(|e| e.refine(&root))
}

impl PathError {
    /// Inside an internally tagged enum (`eos = { type = "hugoniot", c0 = "abc" }`) serde
    /// reports a wrong value without its field; where exactly one field of the table the
    /// path ends at holds the value the message quotes, this adds that field to the path.
    fn refine(mut self, root: &toml::Value) -> Self {
        let Some(quoted) = ["invalid type: ", "invalid value: "]
            .iter()
            .find_map(|p| self.msg.strip_prefix(p))
            .and_then(|rest| rest.split(", expected").next())
        else {
            return self;
        };
        let mut at = root;
        for seg in self.rev_path.iter().rev() {
            let next = match (seg, at) {
                (Seg::Key(k), toml::Value::Table(t)) => t.get(k),
                (Seg::Index(i), toml::Value::Array(a)) => a.get(*i),
                _ => None,
            };
            match next {
                Some(v) => at = v,
                None => return self,
            }
        }
        let toml::Value::Table(at) = at else {
            return self;
        };
        let mut hits = at.iter().filter(|(_, v)| unexpected(v) == quoted);
        if let (Some((k, _)), None) = (hits.next(), hits.next()) {
            self.rev_path.insert(0, Seg::Key(k.clone()));
        }
        self
    }
}

/// How serde's `Unexpected` describes a TOML value (`string "abc"`, `integer `3``).
fn unexpected(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => format!("string {s:?}"),
        toml::Value::Integer(i) => format!("integer `{i}`"),
        toml::Value::Float(x) => {
            let s = format!("{x}");
            if x.is_finite() && !s.contains('.') {
                format!("floating point `{s}.0`")
            } else {
                format!("floating point `{s}`")
            }
        }
        toml::Value::Boolean(b) => format!("boolean `{b}`"),
        toml::Value::Datetime(d) => format!("string {:?}", d.to_string()),
        toml::Value::Array(_) => "sequence".into(),
        toml::Value::Table(_) => "map".into(),
    }
}

/// The error for an array given where a table is expected. Serde's derived structs and
/// internally tagged enums accept a sequence and fill their fields by position
/// (`options = [0.0, 0.0]` would set `av_alpha` and `av_beta`); a scene never means that.
fn expected_table() -> PathError {
    de::Error::custom("expected a table, found an array")
}

/// Whether `visitor` builds a struct or an internally tagged enum, which a TOML table
/// describes: a derived struct visitor expects `struct NAME`, an internally tagged enum's
/// `internally tagged enum NAME` (serde_derive's wording; `scene::library` tests pin it
/// with `eos = [...]`). An internally tagged enum reaches the deserializer through
/// `deserialize_any`, so the visitor's `expecting` is the only sign of what it wants.
fn expects_table<'de, V: Visitor<'de>>(visitor: &V) -> bool {
    struct Expecting<'a, V>(&'a V);
    impl<'de, V: Visitor<'de>> fmt::Display for Expecting<'_, V> {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            self.0.expecting(f)
        }
    }
    let what = Expecting(visitor).to_string();
    what.starts_with("struct ") || what.starts_with("internally tagged enum ")
}

struct ValueDe(toml::Value);

impl<'de> de::Deserializer<'de> for ValueDe {
    type Error = PathError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, PathError> {
        match self.0 {
            toml::Value::String(s) => visitor.visit_string(s),
            toml::Value::Integer(i) => visitor.visit_i64(i),
            toml::Value::Float(x) => visitor.visit_f64(x),
            toml::Value::Boolean(b) => visitor.visit_bool(b),
            toml::Value::Datetime(d) => visitor.visit_string(d.to_string()),
            toml::Value::Array(_) if expects_table(&visitor) => Err(expected_table()),
            toml::Value::Array(a) => {
                let len = a.len();
                let mut seq = Seq(a.into_iter().enumerate());
                let out = visitor.visit_seq(&mut seq)?;
                if seq.0.len() > 0 {
                    return Err(de::Error::invalid_length(len, &"fewer elements"));
                }
                Ok(out)
            }
            toml::Value::Table(t) => visitor.visit_map(Map {
                it: t.into_iter(),
                pending: None,
            }),
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, PathError> {
        visitor.visit_some(self)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, PathError> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, PathError> {
        match self.0 {
            toml::Value::Array(_) => Err(expected_table()),
            other => ValueDe(other).deserialize_any(visitor),
        }
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, PathError> {
        match self.0 {
            toml::Value::String(s) => visitor.visit_enum(s.into_deserializer()),
            other => ValueDe(other).deserialize_any(visitor),
        }
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        unit unit_struct seq tuple tuple_struct map identifier ignored_any
    }
}

struct Seq(std::iter::Enumerate<std::vec::IntoIter<toml::Value>>);

impl<'de> SeqAccess<'de> for Seq {
    type Error = PathError;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, PathError> {
        match self.0.next() {
            None => Ok(None),
            Some((i, v)) => seed
                .deserialize(ValueDe(v))
                .map(Some)
                .map_err(|e| e.within(Seg::Index(i))),
        }
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.0.len())
    }
}

struct Map {
    it: toml::map::IntoIter,
    pending: Option<(String, toml::Value)>,
}

impl<'de> MapAccess<'de> for Map {
    type Error = PathError;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, PathError> {
        match self.it.next() {
            None => Ok(None),
            Some((k, v)) => {
                let name: de::value::StringDeserializer<PathError> = k.clone().into_deserializer();
                let key = seed.deserialize(name)?;
                self.pending = Some((k, v));
                Ok(Some(key))
            }
        }
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, PathError> {
        let (k, v) = self
            .pending
            .take()
            .ok_or_else(|| <PathError as de::Error>::custom("value asked for before its key"))?;
        seed.deserialize(ValueDe(v))
            .map_err(|e| e.within(Seg::Key(k)))
    }
}
