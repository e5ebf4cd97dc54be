//! The mutations that take a generated file away from valid: tokens and lines
//! deleted, doubled, swapped or replaced by garbage, bytes inserted, the file cut.

use std::fmt;

use proptest::prelude::*;

use crate::generate::{number, Mode};

/// The bytes of a file, shown as text with escapes when a case fails.
#[derive(Clone, PartialEq)]
pub(crate) struct Bytes(pub(crate) Vec<u8>);

impl fmt::Debug for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "b\"{}\"", self.0.escape_ascii())
    }
}

/// A position in a file: taken modulo the number of tokens, lines or bytes
/// there are, and shrunk towards the start.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Index(pub(crate) usize);

impl Index {
    fn index(self, len: usize) -> usize {
        self.0 % len
    }
}

pub(crate) fn index() -> impl Strategy<Value = Index> {
    any::<usize>().prop_map(Index)
}

/// One change to a file's bytes.
#[derive(Debug, Clone)]
pub(crate) enum Mutation {
    DeleteToken(Index),
    DuplicateToken(Index),
    ReplaceToken(Index, String),
    InsertToken(Index, String),
    DeleteLine(Index),
    DuplicateLine(Index),
    SwapLines(Index, Index),
    InsertBytes(Index, Vec<u8>),
    Truncate(Index),
}

/// Byte ranges of whitespace-separated tokens.
pub(crate) fn token_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = None;
    for (i, b) in bytes.iter().enumerate() {
        match (b.is_ascii_whitespace(), start) {
            (true, Some(s)) => {
                spans.push((s, i));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        spans.push((s, bytes.len()));
    }
    spans
}

/// Byte ranges of lines, each with its newline.
pub(crate) fn line_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = 0;
    for (i, b) in bytes.iter().enumerate() {
        if *b == b'\n' {
            spans.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < bytes.len() {
        spans.push((start, bytes.len()));
    }
    spans
}

pub(crate) fn splice(bytes: &mut Vec<u8>, (start, end): (usize, usize), with: &[u8]) {
    bytes.splice(start..end, with.iter().copied());
}

impl Mutation {
    pub(crate) fn apply(&self, bytes: &mut Vec<u8>) {
        let tokens = token_spans(bytes);
        let lines = line_spans(bytes);
        let token = |i: &Index| (!tokens.is_empty()).then(|| tokens[i.index(tokens.len())]);
        let line = |i: &Index| (!lines.is_empty()).then(|| lines[i.index(lines.len())]);
        match self {
            Mutation::DeleteToken(i) => {
                if let Some(span) = token(i) {
                    splice(bytes, span, b"");
                }
            }
            Mutation::DuplicateToken(i) => {
                if let Some((s, e)) = token(i) {
                    let copy = [&bytes[s..e], b" "].concat();
                    splice(bytes, (s, s), &copy);
                }
            }
            Mutation::ReplaceToken(i, with) => {
                if let Some(span) = token(i) {
                    splice(bytes, span, with.as_bytes());
                }
            }
            Mutation::InsertToken(i, with) => {
                let at = token(i).map_or(0, |(s, _)| s);
                splice(bytes, (at, at), format!("{with} ").as_bytes());
            }
            Mutation::DeleteLine(i) => {
                if let Some(span) = line(i) {
                    splice(bytes, span, b"");
                }
            }
            Mutation::DuplicateLine(i) => {
                if let Some((s, e)) = line(i) {
                    let mut copy = bytes[s..e].to_vec();
                    if copy.last() != Some(&b'\n') {
                        copy.insert(0, b'\n');
                    }
                    splice(bytes, (e, e), &copy);
                }
            }
            Mutation::SwapLines(a, b) => {
                if let (Some(a), Some(b)) = (line(a), line(b)) {
                    let (first, second) = if a.0 <= b.0 { (a, b) } else { (b, a) };
                    if first.1 <= second.0 {
                        let (x, y) = (bytes[first.0..first.1].to_vec(), bytes[second.0..second.1].to_vec());
                        splice(bytes, second, &x);
                        splice(bytes, first, &y);
                    }
                }
            }
            Mutation::InsertBytes(i, with) => {
                let at = i.index(bytes.len() + 1);
                splice(bytes, (at, at), with);
            }
            Mutation::Truncate(i) => {
                let at = i.index(bytes.len() + 1);
                bytes.truncate(at);
            }
        }
    }
}

/// A replacement token: numbers of every kind, keywords and punctuation of the
/// three formats, and odd text.
pub(crate) fn garbage() -> BoxedStrategy<String> {
    prop_oneof![
        3 => number(Mode::Wild),
        2 => prop::sample::select(vec![
            "v", "f", "s", "p", "pp", "c", "l", "b", "vn", "vt", "o", "g", "usemtl", "mtllib", "newmtl", "Kd", "Ns", "d",
            "from", "at", "up", "angle", "hither", "resolution", "[[object]]", "[[light]]", "[image]", "[camera]",
            "[render]", "[[include]]", "[material.a]", "type", "=", "[", "]", "{", "}", ",", "\"", "'", "#", "/", "//",
            "1/2/3", "-1//-1", "\"sphere\"", "\"mesh\"", "true", "\"\"\"", "\\", "\u{0}", "\r", "é", "\u{202e}", "\u{feff}",
        ])
        .prop_map(String::from),
        1 => "\\PC{0,12}",
        1 => "[ -~]{0,6}",
    ]
    .boxed()
}

pub(crate) fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        2 => index().prop_map(Mutation::DeleteToken),
        1 => index().prop_map(Mutation::DuplicateToken),
        3 => (index(), garbage()).prop_map(|(i, g)| Mutation::ReplaceToken(i, g)),
        2 => (index(), garbage()).prop_map(|(i, g)| Mutation::InsertToken(i, g)),
        1 => index().prop_map(Mutation::DeleteLine),
        1 => index().prop_map(Mutation::DuplicateLine),
        1 => (index(), index()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        1 => (index(), prop::collection::vec(any::<u8>(), 1..6)).prop_map(|(i, b)| Mutation::InsertBytes(i, b)),
        1 => index().prop_map(Mutation::Truncate),
    ]
}

/// A file from `text` with up to four mutations, or now and then pure noise.
pub(crate) fn mutated(text: BoxedStrategy<String>, alphabet: &'static str) -> BoxedStrategy<Bytes> {
    // A third untouched, a third with one change, a third with two to four.
    let mutations = prop_oneof![Just(Vec::new()), prop::collection::vec(mutation(), 1..2), prop::collection::vec(mutation(), 2..5)];
    let near_valid = (text, mutations).prop_map(|(text, mutations)| {
        let mut bytes = text.into_bytes();
        for m in &mutations {
            m.apply(&mut bytes);
        }
        Bytes(bytes)
    });
    prop_oneof![
        16 => near_valid,
        1 => prop::collection::vec(any::<u8>(), 0..400).prop_map(Bytes),
        1 => prop::collection::vec(prop::sample::select(alphabet.as_bytes().to_vec()), 0..400).prop_map(Bytes),
    ]
    .boxed()
}
