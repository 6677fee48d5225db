//! A YAML file as a tree of nodes that remember where they are written, so that a value can be
//! found by its path (`materials.a.kd`, `lights.L.intensity`, `objects.ball.sphere.center`) and
//! replaced in the text itself: the rest of the file, its comments and its layout, stay as the
//! author wrote them. Homework variants are made this way.

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_saphyr::Spanned;

/// A node of the file and where it starts.
pub type Node = Spanned<Kind>;

#[derive(Debug)]
pub enum Kind {
    /// A scalar as written (numbers keep their text: `0.2`, `1.0`).
    Scalar(String),
    Seq(Vec<Node>),
    Map(Vec<(String, Node)>),
}

impl<'de> Deserialize<'de> for Kind {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Kind, D::Error> {
        struct Any;
        impl<'de> Visitor<'de> for Any {
            type Value = Kind;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("any YAML value")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Kind, E> {
                Ok(Kind::Scalar(s.into()))
            }
            fn visit_f64<E: de::Error>(self, x: f64) -> Result<Kind, E> {
                Ok(Kind::Scalar(format!("{x}")))
            }
            fn visit_u64<E: de::Error>(self, x: u64) -> Result<Kind, E> {
                Ok(Kind::Scalar(format!("{x}")))
            }
            fn visit_i64<E: de::Error>(self, x: i64) -> Result<Kind, E> {
                Ok(Kind::Scalar(format!("{x}")))
            }
            fn visit_bool<E: de::Error>(self, x: bool) -> Result<Kind, E> {
                Ok(Kind::Scalar(format!("{x}")))
            }
            fn visit_unit<E: de::Error>(self) -> Result<Kind, E> {
                Ok(Kind::Scalar(String::new()))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut a: A) -> Result<Kind, A::Error> {
                let mut items = vec![];
                while let Some(x) = a.next_element::<Node>()? {
                    items.push(x);
                }
                Ok(Kind::Seq(items))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut a: A) -> Result<Kind, A::Error> {
                let mut entries = vec![];
                while let Some((k, v)) = a.next_entry::<String, Node>()? {
                    entries.push((k, v));
                }
                Ok(Kind::Map(entries))
            }
        }
        d.deserialize_any(Any)
    }
}

pub fn parse(text: &str) -> Result<Node, String> {
    serde_saphyr::from_str::<Node>(text).map_err(|e| {
        let msg = e.to_string();
        msg.lines().next().unwrap_or("not YAML").to_string()
    })
}

/// The node at a dotted path: a key of a mapping, or in a list the item whose `name` is that
/// step (or whose index it is).
pub fn find<'n>(root: &'n Node, path: &str) -> Option<&'n Node> {
    let mut node = root;
    for step in path.split('.') {
        node = match &node.value {
            Kind::Map(entries) => entries.iter().find(|(k, _)| k == step).map(|(_, v)| v)?,
            Kind::Seq(items) => items
                .iter()
                .find(|item| match &item.value {
                    Kind::Map(e) => e.iter().any(|(k, v)| {
                        k == "name" && matches!(&v.value, Kind::Scalar(s) if s == step)
                    }),
                    _ => false,
                })
                .or_else(|| step.parse::<usize>().ok().and_then(|i| items.get(i)))?,
            Kind::Scalar(_) => return None,
        };
    }
    Some(node)
}

/// The text of a node as written, for a scalar or a list of scalars (`0.2`, `[0, 0, 8]`).
pub fn shown(text: &str, node: &Node) -> Option<String> {
    match &node.value {
        Kind::Scalar(_) => Some(slice(text, node)?.to_string()),
        Kind::Seq(items) => {
            let parts: Option<Vec<String>> = items.iter().map(|i| shown(text, i)).collect();
            Some(format!("[{}]", parts?.join(", ")))
        }
        Kind::Map(_) => None,
    }
}

/// The byte range of a scalar in the text.
fn range(text: &str, node: &Node) -> Option<std::ops::Range<usize>> {
    let span = node.referenced.span();
    let start = span.byte_offset()? as usize;
    let len: usize = text
        .get(start..)?
        .chars()
        .take(span.len() as usize)
        .map(char::len_utf8)
        .sum();
    Some(start..start + len)
}

fn slice<'t>(text: &'t str, node: &Node) -> Option<&'t str> {
    text.get(range(text, node)?)
}

/// One change to the text: a byte range and what replaces it.
pub type Edit = (std::ops::Range<usize>, String);

/// The edits that write `values` at a node: a scalar gets one number (or a `[x, y, z]` list);
/// a list of scalars gets one value per item (one number repeated over all of them).
pub fn edits(text: &str, node: &Node, values: &[String]) -> Result<Vec<Edit>, String> {
    match (&node.value, values) {
        (Kind::Scalar(_), [one]) => {
            Ok(vec![(range(text, node).ok_or("no position")?, one.clone())])
        }
        (Kind::Scalar(_), many) => Ok(vec![(
            range(text, node).ok_or("no position")?,
            format!("[{}]", many.join(", ")),
        )]),
        (Kind::Seq(items), _) if items.iter().all(|i| matches!(i.value, Kind::Scalar(_))) => {
            if values.len() != 1 && values.len() != items.len() {
                return Err(format!(
                    "{} values for a list of {}",
                    values.len(),
                    items.len()
                ));
            }
            items
                .iter()
                .enumerate()
                .map(|(k, item)| {
                    let v = if values.len() == 1 {
                        &values[0]
                    } else {
                        &values[k]
                    };
                    Ok((range(text, item).ok_or("no position")?, v.clone()))
                })
                .collect()
        }
        _ => Err("not a number or a list of numbers".into()),
    }
}

/// The text with the edits made (they must not overlap).
pub fn apply(text: &str, mut edits: Vec<Edit>) -> String {
    edits.sort_by_key(|(r, _)| std::cmp::Reverse(r.start));
    let mut out = text.to_string();
    for (r, with) in edits {
        out.replace_range(r, &with);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "# a comment stays\nambient: 0.3\nlights:\n  - { name: L, point: [5, 10, -5], intensity: 1.0 }\nmaterials:\n  a: { color: 1, kd: 0.2 }  # Ä note\nobjects:\n  - name: ball\n    sphere: { center: [0, 0, 8], radius: 5 }\n";

    #[test]
    fn values_are_found_by_path_and_replaced_in_place() {
        let root = parse(SCENE).unwrap();
        let kd = find(&root, "materials.a.kd").unwrap();
        assert_eq!(shown(SCENE, kd).unwrap(), "0.2");
        let centre = find(&root, "objects.ball.sphere.center").unwrap();
        assert_eq!(shown(SCENE, centre).unwrap(), "[0, 0, 8]");
        assert_eq!(
            shown(SCENE, find(&root, "lights.L.intensity").unwrap()).unwrap(),
            "1.0"
        );
        assert!(find(&root, "materials.b.kd").is_none());
        let mut all = edits(SCENE, kd, &["0.35".into()]).unwrap();
        all.extend(edits(SCENE, centre, &["1".into(), "-2".into(), "8.5".into()]).unwrap());
        let out = apply(SCENE, all);
        assert!(out.contains("a: { color: 1, kd: 0.35 }  # Ä note"), "{out}");
        assert!(out.contains("center: [1, -2, 8.5]"), "{out}");
        assert!(out.starts_with("# a comment stays\nambient: 0.3\n"));
    }
}
