//! Generated scene files list their objects one to a line, in the plainest flow style:
//!
//! ```yaml
//!   - { sphere: { center: [0.3794, 2.4523, 2.2536], radius: 0.12 }, material: m20 }
//! ```
//!
//! Items of that shape are read here directly, about eight times faster than the YAML parser
//! reads them, into the very values (positions included) the parser gives. What is read is
//! narrow on purpose: a mapping of `name`, `material` and one of `sphere`, `plane` or `box`,
//! each key once; names of letters, digits, `_` and `-` that no YAML schema reads as anything
//! but a string; numbers as Rust (and so the parser) reads them, within the scene's magnitude.
//! One item that is anything else, and the whole file goes to the parser (`load`), which
//! also says what is wrong with it.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use serde::de::value::{Error as PartError, MapDeserializer, SeqDeserializer};
use serde::de::{Deserializer, IntoDeserializer, Visitor};
use serde::{forward_to_deserialize_any, Deserialize};
use serde_saphyr::{Location, Spanned};

use super::format::{BoxSpec, Num, ObjectSpec, PlaneSpec, SphereSpec, MAX_MAGNITUDE, V3};
use super::split::{content, ObjectList};

/// The items of `list` from the `first`, read directly and added to `objects` in order;
/// false (and `objects` of no use) if one of them is not a simple item. Each item is written
/// once, where it stays: 10 000 of them are 3.5 MB, and a copy of that is noticed.
pub fn read(
    text: &str,
    list: &ObjectList,
    first: usize,
    objects: &mut Vec<Spanned<ObjectSpec>>,
) -> bool {
    let Some(items) = list.items.get(first..) else {
        return false;
    };
    let ends = items.iter().skip(1).copied().chain([list.end]);
    // Each item's line number and the characters before it (positions count characters):
    // a running count over the text, cheap beside the reading.
    let mut places = Vec::with_capacity(items.len());
    let (mut at, mut line, mut chars) = (0, 1, 0);
    for (&start, end) in items.iter().zip(ends) {
        let before = &text.as_bytes()[at..start];
        line += before.iter().filter(|&&b| b == b'\n').count() as u64;
        chars += before.iter().filter(|&&b| is_char_start(b)).count() as u64;
        at = start;
        places.push(Line {
            text: &text[start..end],
            at: start as u64,
            number: line,
            chars,
        });
    }
    let simple = AtomicBool::new(true);
    objects.par_extend(places.par_iter().map(|line| {
        line.item().unwrap_or_else(|| {
            simple.store(false, Ordering::Relaxed);
            Spanned::new(ObjectSpec::default(), Location::UNKNOWN, Location::UNKNOWN)
        })
    }));
    simple.into_inner()
}

/// A byte that starts a character in UTF-8 (not a continuation byte).
fn is_char_start(b: u8) -> bool {
    (b as i8) >= -0x40
}

/// An item's text (its line and any blank or comment lines after it) and where it starts.
struct Line<'a> {
    text: &'a str,
    /// Byte offset of the line in the file.
    at: u64,
    /// Line number, from 1.
    number: u64,
    /// Characters in the file before the line.
    chars: u64,
}

impl<'a> Line<'a> {
    /// The item, if it is simple.
    fn item(&self) -> Option<Spanned<ObjectSpec>> {
        let mut lines = self.text.split_inclusive('\n');
        let code = content(lines.next()?);
        if lines.any(|l| !content(l).trim().is_empty()) {
            return None; // more than one line
        }
        let mut c = Cursor {
            line: self,
            code: code.as_bytes(),
            pos: 0,
        };
        c.spaces();
        c.eat(b'-')?;
        if !c.spaces() {
            return None;
        }
        let item = c.object()?;
        c.spaces();
        (c.pos == code.len()).then_some(item)
    }

    /// The parser's location of a token of `len` bytes at byte `pos` of the line (everything
    /// before it on the line is ASCII, so bytes are characters there).
    fn location(&self, pos: usize, len: usize) -> Location {
        let (pos, len) = (pos as u64, len as u64);
        let parts = Part::Location {
            line: self.number,
            column: pos + 1,
            offset: self.chars + pos,
            byte_offset: self.at + pos,
            len,
        };
        Location::deserialize(parts).expect("a location's parts")
    }
}

/// Reads one line of flow YAML, left to right.
struct Cursor<'a> {
    line: &'a Line<'a>,
    code: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    /// Skips spaces; whether there were any.
    fn spaces(&mut self) -> bool {
        let from = self.pos;
        while self.code.get(self.pos) == Some(&b' ') {
            self.pos += 1;
        }
        self.pos > from
    }

    fn eat(&mut self, b: u8) -> Option<()> {
        (self.code.get(self.pos) == Some(&b)).then(|| self.pos += 1)
    }

    /// A run of the characters names and numbers are made of, and where it starts.
    fn word(&mut self) -> Option<(&'a str, usize)> {
        let from = self.pos;
        while self
            .code
            .get(self.pos)
            .is_some_and(|&b| b.is_ascii_alphanumeric() || matches!(b, b'_' | b'-' | b'+' | b'.'))
        {
            self.pos += 1;
        }
        let word = std::str::from_utf8(&self.code[from..self.pos]).ok()?;
        (!word.is_empty()).then_some((word, from))
    }

    /// `{ key: value, … }`, each value read by `entry` (which refuses keys it does not know).
    fn map(&mut self, mut entry: impl FnMut(&mut Self, &str) -> Option<()>) -> Option<()> {
        self.eat(b'{')?;
        loop {
            self.spaces();
            let (key, _) = self.word()?;
            self.eat(b':')?;
            if !self.spaces() {
                return None;
            }
            entry(self, key)?;
            self.spaces();
            match self.code.get(self.pos)? {
                b',' => self.pos += 1,
                b'}' => {
                    self.pos += 1;
                    return Some(());
                }
                _ => return None,
            }
        }
    }

    /// An object: its name, its material and its shape.
    fn object(&mut self) -> Option<Spanned<ObjectSpec>> {
        let open = self.pos;
        let mut object = ObjectSpec::default();
        let mut shapes = 0;
        self.map(|c, key| {
            shapes += matches!(key, "sphere" | "plane" | "box") as usize;
            match key {
                "name" => once(&mut object.name, c.name().map(|n| n.value)),
                "material" => once(&mut object.material, c.name()),
                "sphere" => once(&mut object.sphere, c.sphere().map(Box::new)),
                "plane" => once(&mut object.plane, c.plane().map(Box::new)),
                "box" => once(&mut object.aabox, c.aabox().map(Box::new)),
                _ => None,
            }
        })?;
        (shapes == 1).then(|| self.spanned(object, open, 1))
    }

    fn sphere(&mut self) -> Option<SphereSpec> {
        let (center, radius) =
            self.pair(("center", Cursor::plain_vector), ("radius", Cursor::number))?;
        Some(SphereSpec { center, radius })
    }

    fn plane(&mut self) -> Option<PlaneSpec> {
        let (point, normal) =
            self.pair(("point", Cursor::plain_vector), ("normal", Cursor::vector))?;
        Some(PlaneSpec { point, normal })
    }

    fn aabox(&mut self) -> Option<BoxSpec> {
        let (min, max) = self.pair(("min", Cursor::vector), ("max", Cursor::plain_vector))?;
        Some(BoxSpec { min, max })
    }

    /// `{ a: …, b: … }` with the keys in either order, each once, both there.
    fn pair<A, B>(
        &mut self,
        (key_a, read_a): (&str, fn(&mut Self) -> Option<A>),
        (key_b, read_b): (&str, fn(&mut Self) -> Option<B>),
    ) -> Option<(A, B)> {
        let (mut a, mut b) = (None, None);
        self.map(|c, key| match key {
            _ if key == key_a => once(&mut a, read_a(c)),
            _ if key == key_b => once(&mut b, read_b(c)),
            _ => None,
        })?;
        Some((a?, b?))
    }

    /// `[x, y, z]`, without its position.
    fn plain_vector(&mut self) -> Option<V3> {
        self.vector().map(|v| v.value)
    }

    /// `[x, y, z]`.
    fn vector(&mut self) -> Option<Spanned<V3>> {
        let open = self.pos;
        self.eat(b'[')?;
        let mut v = [0.0; 3];
        for (i, x) in v.iter_mut().enumerate() {
            self.spaces();
            *x = self.number()?.value.0;
            self.spaces();
            self.eat(if i < 2 { b',' } else { b']' })?;
        }
        Some(self.spanned(V3(v.into()), open, 1))
    }

    /// A decimal number, `[-+]d[.d][(e|E)[-+]d]` (d one digit or more), as Rust reads it and
    /// so as the parser reads a float (`str::parse`), and finite within the scene's limit.
    fn number(&mut self) -> Option<Spanned<Num>> {
        let (word, at) = self.word()?;
        let b = word.as_bytes();
        let mut i = 0;
        let digits = |i: &mut usize| {
            let from = *i;
            while b.get(*i).is_some_and(u8::is_ascii_digit) {
                *i += 1;
            }
            *i > from
        };
        let sign = |i: &mut usize| *i += matches!(b.get(*i), Some(b'-' | b'+')) as usize;
        sign(&mut i);
        let mut decimal = digits(&mut i);
        if b.get(i) == Some(&b'.') {
            i += 1;
            decimal &= digits(&mut i);
        }
        if matches!(b.get(i), Some(b'e' | b'E')) {
            i += 1;
            sign(&mut i);
            decimal &= digits(&mut i);
        }
        if !decimal || i != b.len() {
            return None;
        }
        let x: f64 = word.parse().ok()?;
        let fits = x.is_finite() && x.abs() <= MAX_MAGNITUDE;
        fits.then(|| self.spanned(Num(x), at, word.len()))
    }

    /// A name: a letter or `_`, then letters, digits, `_` and `-`; not one of the words a YAML
    /// schema reads as null or a boolean.
    fn name(&mut self) -> Option<Spanned<String>> {
        let (word, at) = self.word()?;
        let b = word.as_bytes();
        let plain = (b[0].is_ascii_alphabetic() || b[0] == b'_')
            && b.iter()
                .all(|&c| c.is_ascii_alphanumeric() || c == b'_' || c == b'-');
        const SPECIAL: [&str; 9] = ["null", "true", "false", "yes", "no", "on", "off", "y", "n"];
        let special = SPECIAL.iter().any(|s| s.eq_ignore_ascii_case(word));
        (plain && !special).then(|| self.spanned(word.to_string(), at, word.len()))
    }

    /// A value with the location of its first `len` bytes at `pos`, as the parser spans it.
    fn spanned<T>(&self, value: T, pos: usize, len: usize) -> Spanned<T> {
        let at = self.line.location(pos, len);
        Spanned::new(value, at, at)
    }
}

/// A key's value put in its slot; None (not simple) where the key came before, or where its
/// value is not simple.
fn once<T>(slot: &mut Option<T>, value: Option<T>) -> Option<()> {
    if slot.is_some() {
        return None;
    }
    *slot = Some(value?);
    Some(())
}

/// A parser `Location`, or a part of one, for its `Deserialize`: its fields are the parser's
/// own, and that is the way to make one outside it.
#[derive(Clone, Copy)]
enum Part {
    Number(u64),
    Pair(u64, u64),
    /// `Span`: characters from the start and long, and the same in bytes (all ASCII here).
    Span {
        offset: u64,
        byte_offset: u64,
        len: u64,
    },
    Location {
        line: u64,
        column: u64,
        offset: u64,
        byte_offset: u64,
        len: u64,
    },
}

impl<'de> Deserializer<'de> for Part {
    type Error = PartError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, PartError> {
        match self {
            Part::Number(n) => visitor.visit_u64(n),
            Part::Pair(a, b) => visitor.visit_seq(SeqDeserializer::new([a, b].into_iter())),
            Part::Span {
                offset,
                byte_offset,
                len,
            } => visitor.visit_map(MapDeserializer::new(
                [
                    ("offset", Part::Number(offset)),
                    ("len", Part::Number(len)),
                    ("byte_info", Part::Pair(byte_offset, len)),
                ]
                .into_iter(),
            )),
            Part::Location {
                line,
                column,
                offset,
                byte_offset,
                len,
            } => visitor.visit_map(MapDeserializer::new(
                [
                    ("line", Part::Number(line)),
                    ("column", Part::Number(column)),
                    (
                        "span",
                        Part::Span {
                            offset,
                            byte_offset,
                            len,
                        },
                    ),
                    ("source_id", Part::Number(0)),
                ]
                .into_iter(),
            )),
        }
    }

    forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map struct enum
        identifier ignored_any
    }
}

impl IntoDeserializer<'_, PartError> for Part {
    type Deserializer = Part;

    fn into_deserializer(self) -> Part {
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::format::SceneFile;
    use crate::scene::load::{from_yaml, parse_in_pieces};
    use crate::scene::split::{object_list, MIN_SPLIT_BYTES};
    use proptest::prelude::*;

    /// A scene file around `items` (each one line, or lines, of the object list): settings
    /// with characters beyond ASCII before the list (positions count characters, offsets
    /// bytes), perhaps settings after it, and a comment that makes it large enough to read
    /// this way.
    fn scene(items: &[String], after: bool, crlf: bool) -> String {
        let mut text = String::from(
            "# a scene — the list below is one object a line\n\
             camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\n\
             materials:\n  m: { color: [1, 0, 0], kd: 0.8 }\nobjects:\n",
        );
        for item in items {
            text += item;
        }
        if after {
            text += "lights:\n  - { point: [0, 5, 0], intensity: 1 }\nspp: 4\n";
        }
        text += &format!("# {}\n", "padding ".repeat(MIN_SPLIT_BYTES / 8));
        if crlf {
            text = text.replace('\n', "\r\n");
        }
        text
    }

    /// The scene file as `load` reads it, and as the parser reads it in one piece.
    fn both(text: &str) -> (String, String) {
        let read = parse_in_pieces(text, "f", 2).map(|s| format!("{s:?}"));
        let whole = from_yaml::<SceneFile>(text, "f").map(|s| format!("{s:?}"));
        let show = |r: Result<String, _>| r.unwrap_or_else(|e| format!("error: {e}"));
        (show(read), show(whole))
    }

    /// Whether the items after the first are read here.
    fn read_here(text: &str) -> bool {
        read(
            text,
            &object_list(text).expect("a block list"),
            1,
            &mut vec![],
        )
    }

    /// Numbers spelled the ways scene files spell them.
    fn number() -> impl Strategy<Value = String> {
        (-1e4..1e4f64, 0u8..9).prop_map(|(x, style)| match style {
            0 => format!("{x}"),
            1 => format!("{x:e}"),
            2 => format!("{x:E}"),
            3 => format!("{x:.3}"),
            4 => format!("{}", x as i64),
            5 => format!("+{}", x.abs()),
            6 => format!("{x:.25}"),
            7 => "-0".to_string(),
            _ => format!("{}e-{}", x.abs() as u64, x.abs() as u64 % 300),
        })
    }

    /// Names no schema reads as anything but a string.
    fn name() -> impl Strategy<Value = String> {
        "[a-zA-Z_][a-zA-Z0-9_-]{0,5}".prop_filter("a plain name", |n| {
            !["null", "true", "false", "yes", "no", "on", "off", "y", "n"]
                .iter()
                .any(|s| s.eq_ignore_ascii_case(n))
        })
    }

    /// `[x, y, z]` with spaces or none.
    fn vector(x: &[String], pad: &str) -> String {
        format!("[{pad}{}{pad},{pad}{} ,{}{pad}]", x[0], x[1], x[2])
    }

    prop_compose! {
        /// A simple item: a sphere, plane or box, its keys in any order, with or without a
        /// name and material, spaced in several ways, perhaps with a comment after it.
        fn simple_item()(
            shape in 0u8..3,
            x in prop::collection::vec(number(), 7),
            name in prop::option::of(name()),
            material in prop::option::of(name()),
            order in any::<u8>(),
            tight in any::<bool>(),
            comment in any::<bool>(),
        ) -> String {
            let pad = if tight { "" } else { " " };
            let (a, b) = (vector(&x[..3], pad), vector(&x[3..6], pad));
            let mut inner = match shape {
                0 => vec![format!("center: {a}"), format!("radius:  {}", x[6])],
                1 => vec![format!("point: {a}"), format!("normal: {b}")],
                _ => vec![format!("min: {a}"), format!("max: {b}")],
            };
            if order & 1 != 0 {
                inner.reverse();
            }
            let shape = ["sphere", "plane", "box"][shape as usize];
            let mut keys = vec![format!("{shape}: {{{pad}{}{pad}}}", inner.join(", "))];
            keys.extend(name.map(|n| format!("name: {n}")));
            keys.extend(material.map(|m| format!("material: {m}")));
            let turn = order as usize % keys.len();
            keys.rotate_left(turn);
            let comment = if comment { "   # é, a comment" } else { "" };
            format!("  - {{{pad}{}{pad}}}{comment}\n", keys.join(&format!("{pad}, ")))
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        /// Simple items are read here, to the values and positions the parser gives them.
        #[test]
        fn simple_items_read_as_the_parser_reads_them(
            items in prop::collection::vec(simple_item(), 2..30),
            after in any::<bool>(),
            crlf in any::<bool>(),
        ) {
            let text = scene(&items, after, crlf);
            prop_assert!(read_here(&text));
            let (read, whole) = both(&text);
            prop_assert!(!whole.starts_with("error"), "{}", whole);
            prop_assert_eq!(read, whole);
        }

        /// One item the reader does not take, anywhere in the list, and the parser reads the
        /// file (and says what is wrong with it) as it would anyway.
        #[test]
        fn one_other_item_leaves_the_file_to_the_parser(
            items in prop::collection::vec(simple_item(), 2..20),
            other in 0usize..OTHERS.len(),
            at in any::<prop::sample::Index>(),
        ) {
            let mut items = items;
            let at = 1 + at.index(items.len() - 1);
            items.insert(at, format!("  - {}\n", OTHERS[other]));
            let text = scene(&items, true, false);
            prop_assert!(!read_here(&text), "{}", OTHERS[other]);
            let (read, whole) = both(&text);
            prop_assert_eq!(read, whole);
        }
    }

    /// Items that are not simple: other shapes and keys, special names, numbers the parser
    /// reads otherwise or refuses, a repeated key, more or fewer than one shape, a trailing
    /// comma, a second line.
    const OTHERS: &[&str] = &[
        "{ cylinder: { base: [0, 0, 0], top: [0, 1, 0], radius: 1 } }",
        "{ sphere: { center: [0, 0, 0], radius: 1 }, transform: [ { rotate_y: 30 } ] }",
        "{ name: null, sphere: { center: [0, 0, 0], radius: 1 } }",
        "{ name: Yes, sphere: { center: [0, 0, 0], radius: 1 } }",
        "{ sphere: { center: [0, 0, 0], radius: 1 }, material: off }",
        "{ name: a.b, sphere: { center: [0, 0, 0], radius: 1 } }",
        "{ name: a#b, sphere: { center: [0, 0, 0], radius: 1 } }",
        "{ sphere: { center: [0, 0, 0], radius: .5 } }",
        "{ sphere: { center: [0, 0, 0], radius: 1. } }",
        "{ sphere: { center: [0, 0, 0], radius: 0x10 } }",
        "{ sphere: { center: [0, 0, 0], radius: 1_000 } }",
        "{ sphere: { center: [0, 0, 0], radius: .inf } }",
        "{ sphere: { center: [0, 0, 0], radius: 1e101 } }",
        "{ sphere: { center: [0, 0, 1e400], radius: 1 } }",
        "{ sphere: { center: [0, 0], radius: 1 } }",
        "{ sphere: { center: [0, 0, 0, 0], radius: 1 } }",
        "{ sphere: { center: [0, 0, 0] } }",
        "{ sphere: { center: [0, 0, 0], radius: 1, radius: 2 } }",
        "{ name: a, name: b, sphere: { center: [0, 0, 0], radius: 1 } }",
        "{ sphere: { center: [0, 0, 0], radius: 1 }, box: { min: [0, 0, 0], max: [1, 1, 1] } }",
        "{ name: lonely }",
        "{ sphere: { center: [0, 0, 0], radius: 1 }, }",
        "{ sphere: { center: [0, 0, 0], radius:1 } }",
        "{ sphere: { center: [0, 0, 0], radius: 1 } } extra",
        "{ sphere: { center: [0, 0, 0],\n      radius: 1 } }",
        "{ sphere: { center: [0, 0, 0], radius: 1 } }\n    material: m",
        "name: block\n    sphere: { center: [0, 0, 0], radius: 1 }",
    ];

    #[test]
    fn positions_count_characters_and_lines() {
        let items = [
            "  - { sphere: { center: [0, 0, 0], radius: 1 } }   # ×, é\n".to_string(),
            "\n  # between — items\n".to_string(),
            "  - { name: b, sphere: { center: [1, 2, 3], radius: 0.5 }, material: m }\n"
                .to_string(),
        ];
        let text = scene(&items, false, false);
        let list = object_list(&text).unwrap();
        let mut read_items = vec![];
        assert!(read(&text, &list, 1, &mut read_items), "simple");
        let item = &read_items[0];
        let line = text[..list.items[1]].matches('\n').count() as u64 + 1;
        assert_eq!(
            (item.referenced.line(), item.referenced.column()),
            (line, 5)
        );
        let chars = text[..list.items[1]].chars().count() as u64 + 4;
        assert_eq!(item.referenced.span().offset(), chars);
        assert_eq!(
            item.referenced.span().byte_offset(),
            Some(list.items[1] as u64 + 4)
        );
        let radius = &item.value.sphere.as_ref().unwrap().radius;
        assert_eq!((radius.referenced.column(), radius.value.0), (53, 0.5));
        assert_eq!(radius.referenced.span().len(), 3);
        let (read, whole) = both(&text);
        assert_eq!(read, whole);
    }
}
