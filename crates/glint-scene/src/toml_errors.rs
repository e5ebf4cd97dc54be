//! TOML errors in plain words.
//!
//! The `toml` crate and serde describe a problem in Rust's terms ("invalid
//! type: floating point `3.0`, expected i64"), report the alphabetically
//! first of several unknown keys, list every field of a struct for a typo,
//! and report an unclosed array at the key on the next line. This module turns
//! such an error into one a student can act on:
//!
//! * types in words: "expected a whole number, found 3.0 (write 3)";
//! * an unknown key named first in file order, with the nearest valid key for
//!   that table, or for that type of object ("did you mean `radius`?");
//! * `[object]` for `[[object]]` and the like explained as TOML's two kinds of
//!   table;
//! * an unclosed array reported where it opens.

use std::path::Path;

use serde::de::{self, DeserializeOwned, Deserializer, Visitor};
use toml::de::{DeTable, DeValue};
use toml::Spanned;

use crate::{suggest, LoadError, Location};

/// What the TOML reader knows about its tables.
pub(crate) struct Schema {
    /// The keys of the table at `path` (the keys leading to it, array indices
    /// left out), or `None` where any name is allowed (the names of materials)
    /// or nothing is known.
    pub fields: fn(&[&str]) -> Option<&'static [&'static str]>,
    /// The keys an object of a given `type` takes besides `type` and `material`.
    pub object_keys: fn(&str) -> Option<&'static [&'static str]>,
}

/// The tables of a scene file, as paths for [`Schema::fields`] and as written.
const TABLES: &[(&[&str], &str)] = &[
    (&["image"], "[image]"),
    (&["camera"], "[camera]"),
    (&["ambient"], "[ambient]"),
    (&["render"], "[render]"),
    (&["depth_cue"], "[depth_cue]"),
    (&["light"], "[[light]]"),
    (&["material", "NAME"], "[material.NAME]"),
    (&["object"], "[[object]]"),
    (&["include"], "[[include]]"),
    (&["animation"], "[animation]"),
    (&["animation", "camera"], "[[animation.camera]]"),
    (&["animation", "light"], "[[animation.light]]"),
    (&["animation", "orbit"], "[animation.orbit]"),
];

/// Options of `glint render` that are sometimes written into a scene.
const COMMAND_LINE_ONLY: &[&str] = &["spp", "seed", "filter", "exposure", "tone_map", "bits", "view", "aov"];

/// The field names of a struct that serde derives `Deserialize` for, as it
/// reads them (renames applied): asked of the derived code itself, so they
/// cannot drift from the structs.
pub(crate) fn fields_of<T: DeserializeOwned>() -> &'static [&'static str] {
    let capture = FieldsOf(std::cell::Cell::new(&[]));
    let _ = T::deserialize(&capture);
    capture.0.get()
}

struct FieldsOf(std::cell::Cell<&'static [&'static str]>);

impl<'de> Deserializer<'de> for &FieldsOf {
    type Error = de::value::Error;

    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
        Err(de::Error::custom("only structs have fields"))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        _visitor: V,
    ) -> Result<V::Value, Self::Error> {
        self.0.set(fields);
        Err(de::Error::custom("fields captured"))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf option unit
        unit_struct newtype_struct seq tuple tuple_struct map enum identifier ignored_any
    }
}

/// The error `e` from reading `source` (named `path`) as a scene, in plain words.
pub(crate) fn explain(source: &str, path: &Path, e: &toml::de::Error, schema: &Schema) -> LoadError {
    let raw = e.message().trim().replace('\n', " ");
    let Some(span) = e.span() else {
        return LoadError::new(path, None, plain(&raw));
    };
    let at = |offset: usize, message: String| LoadError::new(path, Some(Location::of_offset(source, offset)), message);
    let doc = match DeTable::parse(source) {
        Ok(doc) => doc,
        // Not TOML at all.
        Err(_) => {
            let (offset, message) = syntax(source, span.start, &raw);
            return at(offset, message);
        }
    };
    // Valid TOML that does not fit the scene format. serde stops at the first
    // problem in its own order (keys alphabetically); problems with the
    // structure and unknown keys are found here in file order, and the first
    // of all is reported. At the same place, the explanation found here wins.
    let mut message = plain(&raw);
    // A table every scene needs.
    if let Some(name) = raw.strip_prefix("missing field `").and_then(|r| r.strip_suffix('`')) {
        if (schema.fields)(&[]).is_some_and(|f| f.contains(&name)) {
            message = format!("missing table [{name}]: every scene has an [image] and a [camera] table");
        }
    }
    let mut found = vec![(span.start, 1, with_key(source, span.start, message))];
    structure(doc.get_ref(), &mut found);
    let mut unknown = Vec::new();
    walk(doc.get_ref(), &mut Vec::new(), schema, &mut unknown);
    found.extend(unknown.into_iter().map(|u| (u.offset, 0, u.message)));
    // Compared by line: serde may name a table's header where the key is named here.
    let line = |offset: usize| Location::of_offset(source, offset).line;
    let (offset, _, message) =
        found.into_iter().min_by_key(|(offset, priority, _)| (line(*offset), *priority, *offset)).expect("serde's own error is there");
    at(offset, message)
}

/// `message` prefixed by the key whose value is wrong: the text before `=` on
/// the line of `offset` (nothing on a table header, or when the message
/// names the key already).
fn with_key(source: &str, offset: usize, message: String) -> String {
    let line = Location::of_offset(source, offset).line;
    let line_text = source.lines().nth(line - 1).unwrap_or("");
    let key = line_text
        .split_once('=')
        .map(|(k, _)| k.trim())
        .filter(|k| !k.is_empty() && !k.starts_with('[') && !message.contains(&format!("`{k}`")));
    match key {
        Some(key) => format!("{key}: {message}"),
        None => message,
    }
}

/// serde's and toml's phrases in plain words.
pub(crate) fn plain(message: &str) -> String {
    let typed = message.strip_prefix("invalid type: ").or_else(|| message.strip_prefix("invalid value: "));
    if let Some((found, expected)) = typed.and_then(|rest| rest.rsplit_once(", expected ")) {
        let expected = expected_words(expected);
        let mut text = format!("expected {expected}, found {}", found_words(found));
        let quoted_number = found.strip_prefix("string \"").and_then(|f| f.strip_suffix('"')).is_some_and(|f| f.trim().parse::<f64>().is_ok());
        if quoted_number && expected.contains("number") {
            text.push_str(" (write the number without quotes)");
        }
        if expected == "a whole number" {
            if let Some(v) = found.strip_prefix("floating point `").and_then(|f| f.strip_suffix('`')) {
                if let Ok(x) = v.parse::<f64>() {
                    if x.fract() == 0.0 && x.abs() < 1e15 {
                        text.push_str(&format!(" (write {x:.0}, without the decimal point)"));
                    }
                }
            }
            if found.ends_with(" as i128") {
                text.push_str(" (far too large)");
            }
        }
        return text;
    }
    if let Some((n, expected)) = message.strip_prefix("invalid length ").and_then(|rest| rest.split_once(", expected ")) {
        let s = if n == "1" { "" } else { "s" };
        return format!("expected {}, found {n} value{s}", expected_words(expected));
    }
    if let Some(rest) = message.strip_prefix("missing field ") {
        return format!("missing key {rest}");
    }
    let known: &[(&str, &str)] = &[
        ("string values must be quoted", "not a value: write numbers as digits (like 1.5) and text in quotes (like \"sphere\")"),
        ("invalid basic string", "the string is not closed: a `\"` is missing"),
        ("unclosed table", "the table header is not closed: a `]` is missing"),
        ("duplicate key", "duplicate key: it is given twice in this table"),
    ];
    for (start, words) in known {
        if message.starts_with(start) {
            return (*words).to_string();
        }
    }
    message.to_string()
}

fn expected_words(expected: &str) -> String {
    match expected {
        "f64" | "f32" => "a number".into(),
        "i64" | "i32" | "i16" | "i8" | "u64" | "u32" | "u16" | "u8" | "i128" | "u128" | "usize" => "a whole number".into(),
        "a boolean" => "`true` or `false`".into(),
        "a string" | "a borrowed string" => "a string in quotes".into(),
        "a sequence" => "an array".into(),
        "a map" => "a table".into(),
        s if s.starts_with("struct ") => "a table".into(),
        s => s.into(),
    }
}

fn found_words(found: &str) -> String {
    let inner = |prefix: &str| found.strip_prefix(prefix).and_then(|f| f.split_once('`')).map(|(v, _)| v.to_string());
    if let Some(s) = found.strip_prefix("string ") {
        return format!("the string {s}");
    }
    if let Some(v) = inner("floating point `").or_else(|| inner("integer `")) {
        return v;
    }
    if let Some(v) = inner("boolean `") {
        return format!("`{v}`");
    }
    match found {
        "map" => "a table".into(),
        "sequence" => "an array".into(),
        other => other.into(),
    }
}

/// The place and message of a TOML syntax error at `offset`: an unclosed
/// array is reported at its opening bracket.
fn syntax(source: &str, offset: usize, raw: &str) -> (usize, String) {
    let array_problem = raw.starts_with("missing comma between array elements") || raw.starts_with("unclosed array");
    // A `[` never closed in the whole file, opened before the error: whatever
    // the parser tripped over next, that is the problem.
    if let Some(open) = unclosed_bracket(source, source.len()).filter(|&open| open <= offset) {
        return (open, with_key(source, open, "this array is not closed: a `]` is missing".into()));
    }
    // `[0 0 0]`: numbers without commas.
    if let Some(open) = unclosed_bracket(source, offset) {
        let line = &source[open + 1..];
        let inner = &line[..line.find(['\n', ']']).unwrap_or(line.len())];
        let numbers: Vec<&str> = inner.split_whitespace().collect();
        if numbers.len() > 1 && !inner.contains(',') && numbers.iter().all(|n| n.parse::<f64>().is_ok()) {
            let fixed = format!("[{}]", numbers.join(", "));
            return (open, with_key(source, open, format!("the values of an array are separated by commas: write {fixed}")));
        }
    }
    if array_problem {
        if let Some(open) = unclosed_bracket(source, offset) {
            let open_line = Location::of_offset(source, open).line;
            let rest = source[offset.min(source.len())..].trim_start();
            let next_is_new_entry = rest.is_empty() || starts_key_value(rest) || starts_header(rest);
            if raw.starts_with("unclosed array") || (Location::of_offset(source, offset).line > open_line && next_is_new_entry) {
                return (open, with_key(source, open, "this array is not closed: a `]` is missing".into()));
            }
        }
    }
    (offset, with_key(source, offset, plain(raw)))
}

/// Whether `text` starts with `key =`.
fn starts_key_value(text: &str) -> bool {
    let key_len = text.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.')).unwrap_or(text.len());
    key_len > 0 && text[key_len..].trim_start_matches([' ', '\t']).starts_with('=')
}

/// Whether `text` starts with a table header, `[name]` or `[[name]]`.
fn starts_header(text: &str) -> bool {
    let name = text.trim_start_matches('[').trim_start();
    text.starts_with('[') && name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_' || c == '"')
}

/// The innermost `[` of a value that is still open at `offset`, read as TOML
/// (strings, comments and table headers skipped).
fn unclosed_bracket(source: &str, offset: usize) -> Option<usize> {
    let bytes = source.as_bytes();
    let end = offset.min(bytes.len());
    let mut stack: Vec<(u8, usize)> = Vec::new();
    let mut in_value = false;
    let mut i = 0;
    let skip_line = |i: usize| bytes[i..end].iter().position(|&b| b == b'\n').map_or(end, |p| i + p);
    while i < end {
        let b = bytes[i];
        match b {
            b'#' => {
                i = skip_line(i);
                continue;
            }
            b'"' | b'\'' => {
                let triple = bytes[i..end].starts_with(&[b, b, b]);
                let mut j = if triple { i + 3 } else { i + 1 };
                while j < end {
                    if b == b'"' && bytes[j] == b'\\' {
                        j += 2;
                        continue;
                    }
                    if triple && bytes[j..end].starts_with(&[b, b, b]) {
                        j += 3;
                        break;
                    }
                    if !triple && (bytes[j] == b || bytes[j] == b'\n') {
                        j += 1;
                        break;
                    }
                    j += 1;
                }
                i = j;
                continue;
            }
            b'=' if stack.last().is_none_or(|(c, _)| *c == b'{') => in_value = true,
            b'[' if in_value || !stack.is_empty() => stack.push((b'[', i)),
            b'[' => {
                // A table header.
                i = skip_line(i);
                continue;
            }
            b']' | b'}' => {
                let open = if b == b']' { b'[' } else { b'{' };
                if stack.last().is_some_and(|(c, _)| *c == open) {
                    stack.pop();
                }
            }
            b'{' => stack.push((b'{', i)),
            b'\n' if stack.is_empty() => in_value = false,
            _ => {}
        }
        i += 1;
    }
    stack.iter().rev().find(|(c, _)| *c == b'[').map(|&(_, at)| at)
}

/// A table written the wrong way: `[object]` for `[[object]]`, `[[image]]`
/// for `[image]`, a material without a name.
fn structure(doc: &DeTable<'_>, found: &mut Vec<(usize, u8, String)>) {
    for (key, value) in doc {
        let name = key.get_ref().as_ref();
        let at = key.span().start;
        match (name, value.get_ref()) {
            ("object" | "light" | "include", DeValue::Table(_)) => found.push((
                at,
                0,
                format!("[{name}] is a single table: write [[{name}]] (an array of tables) for each {name}"),
            )),
            ("image" | "camera" | "ambient" | "render" | "depth_cue" | "animation", DeValue::Array(_)) => found.push((
                at,
                0,
                format!("[[{name}]] is an array of tables, but a scene has one {name}: write [{name}]"),
            )),
            ("material", DeValue::Array(_)) => found.push((
                at,
                0,
                "[[material]] is an array of tables: write [material.NAME] for each material, as in [material.red]".into(),
            )),
            ("animation", DeValue::Table(animation)) => {
                for (key, value) in animation {
                    let name = key.get_ref().as_ref();
                    if matches!(name, "camera" | "light") && matches!(value.get_ref(), DeValue::Table(_)) {
                        found.push((
                            key.span().start,
                            0,
                            format!("[animation.{name}] is a single table: write [[animation.{name}]] (an array of tables) for each key"),
                        ));
                    }
                }
            }
            ("material", DeValue::Table(materials)) => {
                for (key, value) in materials {
                    if !matches!(value.get_ref(), DeValue::Table(_)) {
                        found.push((
                            key.span().start,
                            0,
                            format!(
                                "[material] holds named materials: write [material.NAME] (as in [material.red]) and put `{} = …` below it",
                                key.get_ref()
                            ),
                        ));
                    }
                }
            }
            _ => {}
        }
    }
}

/// An unknown key, where it is and what to say about it.
struct Unknown {
    offset: usize,
    message: String,
}

/// Collects the unknown keys of `table` (at `path`) and of the tables in it.
fn walk<'a>(table: &'a DeTable<'a>, path: &mut Vec<&'a str>, schema: &Schema, out: &mut Vec<Unknown>) {
    let fields = (schema.fields)(path);
    for (key, value) in table {
        let name: &str = key.get_ref().as_ref();
        if fields.is_some_and(|f| !f.contains(&name)) {
            out.push(Unknown { offset: key.span().start, message: unknown_message(name, value, table, path, schema) });
            continue;
        }
        match value.get_ref() {
            DeValue::Table(t) => {
                path.push(name);
                walk(t, path, schema, out);
                path.pop();
            }
            DeValue::Array(items) => {
                for item in items.iter() {
                    if let DeValue::Table(t) = item.get_ref() {
                        path.push(name);
                        walk(t, path, schema, out);
                        path.pop();
                    }
                }
            }
            _ => {}
        }
    }
}

fn string_value<'a>(table: &'a DeTable<'a>, key: &str) -> Option<&'a str> {
    table.iter().find(|(k, _)| k.get_ref().as_ref() == key).and_then(|(_, v)| v.get_ref().as_str())
}

/// How a top-level table `name` is written.
fn table_form(name: &str) -> String {
    match name {
        "object" | "light" | "include" => format!("[[{name}]]"),
        "material" => "[material.NAME]".into(),
        _ => format!("[{name}]"),
    }
}

fn backticked(keys: &[&str]) -> String {
    keys.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")
}

fn unknown_message(key: &str, value: &Spanned<DeValue<'_>>, table: &DeTable<'_>, path: &[&str], schema: &Schema) -> String {
    let fields = (schema.fields)(path).unwrap_or(&[]);
    // Which other table has this key (for an object, a material first; in
    // the animation, another of its tables first).
    let preferred = |p: &[&str]| match path.first() {
        Some(&"object") => p[0] == "material",
        Some(&"animation") => p[0] == "animation",
        _ => true,
    };
    let home = TABLES
        .iter()
        .filter(|(p, _)| preferred(p))
        .chain(TABLES)
        .find(|(p, _)| (schema.fields)(p).is_some_and(|f| f.contains(&key)))
        .map(|(_, shown)| *shown);
    if path.is_empty() {
        let written = match value.get_ref() {
            DeValue::Table(_) => format!("table [{key}]"),
            DeValue::Array(items) if !items.is_empty() && items.iter().all(|i| matches!(i.get_ref(), DeValue::Table(_))) => {
                format!("table [[{key}]]")
            }
            _ => format!("key `{key}`"),
        };
        if let Some(home) = home {
            return format!("unknown {written} at the top of the file: `{key}` belongs in {home}, below its header");
        }
        if let Some(near) = suggest::nearest(key, fields.iter().copied()) {
            return format!("unknown {written}; did you mean {}?", table_form(near));
        }
        let all: Vec<String> = fields.iter().map(|f| table_form(f)).collect();
        return format!("unknown {written}: a scene has the tables {}", all.join(", "));
    }
    let kind = string_value(table, "type");
    let (place, candidates): (String, Vec<&str>) = match (path[0], kind) {
        ("object", Some(kind)) => match (schema.object_keys)(kind) {
            Some(keys) => (format!("a {kind} object"), ["type", "material"].into_iter().chain(keys.iter().copied()).collect()),
            None => ("[[object]]".into(), fields.to_vec()),
        },
        ("light", Some(kind @ ("point" | "directional"))) => (format!("a {kind} light"), fields.to_vec()),
        ("material", _) if path.len() == 2 => (format!("[material.{}]", path[1]), fields.to_vec()),
        ("material", _) if path.len() == 3 => (format!("the {} of [material.{}]", path[2], path[1]), fields.to_vec()),
        ("animation", _) if path.len() == 2 => {
            let shown = TABLES.iter().find(|(p, _)| *p == path).map_or("[animation]", |(_, shown)| *shown);
            (shown.to_string(), fields.to_vec())
        }
        (name, _) => (table_form(name), fields.to_vec()),
    };
    if let Some(near) = suggest::nearest(key, candidates.iter().copied()) {
        return format!("unknown key `{key}` in {place}; did you mean `{near}`?");
    }
    if COMMAND_LINE_ONLY.contains(&key) {
        let option = key.replace('_', "-");
        return format!("unknown key `{key}` in {place}: `{key}` is a command-line option (glint render --{option} …), not a scene key");
    }
    let own = if path[0] == "animation" { place.clone() } else { table_form(path[0]) };
    if let Some(home) = home.filter(|h| *h != own) {
        if path[0] == "object" && home == "[material.NAME]" {
            return format!(
                "unknown key `{key}` in {place}: `{key}` belongs to a material; define it in [material.NAME] and give the object `material = \"NAME\"`"
            );
        }
        return format!("unknown key `{key}` in {place}: `{key}` belongs in {home}");
    }
    format!("unknown key `{key}` in {place}, which takes {}", backticked(&candidates))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_words_for_types() {
        assert_eq!(plain("invalid type: string \"big\", expected f64"), "expected a number, found the string \"big\"");
        assert_eq!(
            plain("invalid type: floating point `3.0`, expected i64"),
            "expected a whole number, found 3.0 (write 3, without the decimal point)"
        );
        assert_eq!(plain("invalid type: floating point `64.5`, expected i64"), "expected a whole number, found 64.5");
        assert_eq!(plain("invalid type: integer `1`, expected a boolean"), "expected `true` or `false`, found 1");
        assert_eq!(plain("invalid type: map, expected a sequence"), "expected an array, found a table");
        assert_eq!(plain("invalid length 4, expected an array of 3 numbers"), "expected an array of 3 numbers, found 4 values");
        assert_eq!(plain("missing field `camera`"), "missing key `camera`");
        assert!(plain("invalid type: integer `99999999999999999999` as i128, expected i64").contains("far too large"));
    }

    #[test]
    fn unclosed_brackets_are_found_where_they_open() {
        let src = "a = [1, 2,\nb = 3\n";
        assert_eq!(unclosed_bracket(src, src.find("b =").unwrap()), Some(4));
        let src = "[image]\nv = [[0, 0], [1, # ]\n 2\nw = 1";
        // The innermost: `[1, ` (the `]` after `#` is a comment).
        assert_eq!(unclosed_bracket(src, src.find("w =").unwrap()), Some(src.find("[1").unwrap()));
        let src = "s = \"[\"\nt = ['[', \"]\"\nu = 1";
        assert_eq!(unclosed_bracket(src, src.find("u =").unwrap()), Some(src.find("['").unwrap()));
        let src = "x = [1, 2]\n[table]\ny = 1";
        assert_eq!(unclosed_bracket(src, src.len()), None);
    }
}
