//! Homework that cannot be copied: a lesson's `exercises.yaml` may declare scene values that
//! vary from student to student,
//!
//! ```yaml
//! vary:
//!   materials.a.kd: [0.1, 0.4]                  # a number in [0.1, 0.4], in steps of 0.01
//!   lights.L.intensity: { between: [0.8, 1.2], step: 0.05 }
//!   objects.ball.sphere.center: [[-1, 0, 7], [1, 0, 9]]   # each coordinate in its range
//!   ambient: { one_of: [0.2, 0.3, 0.4] }
//! ```
//!
//! A path names a key of the scene file, a list item by its `name` (or index). Each student's
//! values are drawn from a generator seeded by the lesson and the student ID alone, so the same
//! student always gets the same homework, and they are written into every scene file of the
//! lesson where the path exists. A question may quote a varied value as `{materials.a.kd}`.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;

use super::error::{LessonError, RangeError};
use super::yaml_spans::{self, Edit};
use crate::files::{read_text, TEXT_BUDGET};
use crate::sampling::Rng;
use crate::trace::text::num;

/// How one value varies.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(
    untagged,
    expecting = "a range: [lo, hi], [[x, y, z], [x, y, z]], { between: [lo, hi], step: s } or { one_of: [...] } of numbers or of [x, y, z]"
)]
pub enum Range {
    /// `[lo, hi]`, in steps of 0.01.
    Numbers([f64; 2]),
    /// `[[x, y, z], [x, y, z]]`: each coordinate in its own range, in steps of 0.01.
    Vectors([[f64; 3]; 2]),
    /// `{ between: [lo, hi], step: s }`.
    Stepped {
        /// [lo, hi]: the values drawn are lo, lo + s, … up to hi.
        between: [f64; 2],
        /// The spacing s of the values drawn, > 0.
        step: f64,
    },
    /// `{ one_of: [...] }`: one of the values listed (numbers or vectors).
    OneOf {
        /// The values listed, each as likely to be drawn.
        one_of: Vec<Pick>,
    },
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum Pick {
    Number(f64),
    Vector([f64; 3]),
}

/// How many whole steps from lo stay within hi (allowing for the rounding of decimal steps):
/// the values drawn are lo + k·step for k from 0 to that.
fn steps(lo: f64, hi: f64, step: f64) -> u64 {
    ((hi - lo) / step + 1e-9).floor() as u64
}

/// Whether the values lo + k·step are written apart from their neighbours (`num`: six
/// decimals, seven significant digits from 10¹⁵ on) at both ends of the range: a finer step
/// would give students values off its grid, or all the same one.
fn written_apart(lo: f64, hi: f64, step: f64) -> bool {
    let n = steps(lo, hi, step) as f64;
    let at = |k: f64| num(lo + k * step);
    n == 0.0 || (at(0.0) != at(1.0) && at(n - 1.0) != at(n))
}

/// The step of a range written without one.
const STEP: f64 = 0.01;

impl Range {
    /// Checks the range can be drawn from.
    pub fn check(&self) -> Result<(), RangeError> {
        let ok = |lo: f64, hi: f64, step: f64| {
            lo.is_finite() && hi.is_finite() && lo <= hi && step > 0.0 && step.is_finite()
        };
        let fine = match self {
            Range::Numbers([lo, hi]) => ok(*lo, *hi, STEP),
            Range::Vectors([lo, hi]) => (0..3).all(|i| ok(lo[i], hi[i], STEP)),
            Range::Stepped { between, step } => {
                let [lo, hi] = *between;
                if ok(lo, hi, *step) && !written_apart(lo, hi, *step) {
                    return Err(RangeError::StepTooFine);
                }
                ok(lo, hi, *step)
            }
            Range::OneOf { one_of } => !one_of.is_empty(),
        };
        if fine {
            Ok(())
        } else {
            Err(RangeError::Shape)
        }
    }

    /// The values a validation tries: the range's low end, its first step and the last step
    /// that stays within it (each coordinate of a vector at once): the ends of what students
    /// draw. Or every value a `one_of` lists.
    pub fn probes(&self) -> Vec<Vec<String>> {
        let ends = |lo: f64, hi: f64, step: f64| {
            let n = steps(lo, hi, step);
            [lo, lo + n.min(1) as f64 * step, lo + n as f64 * step].map(num)
        };
        let column = |k: usize, columns: &[[String; 3]]| -> Vec<String> {
            columns.iter().map(|c| c[k].clone()).collect()
        };
        let mut probes: Vec<Vec<String>> = match self {
            Range::Numbers([lo, hi]) => ends(*lo, *hi, STEP).map(|x| vec![x]).to_vec(),
            Range::Stepped { between, step } => ends(between[0], between[1], *step)
                .map(|x| vec![x])
                .to_vec(),
            Range::Vectors([lo, hi]) => {
                let columns: Vec<[String; 3]> = (0..3).map(|i| ends(lo[i], hi[i], STEP)).collect();
                (0..3).map(|k| column(k, &columns)).collect()
            }
            Range::OneOf { one_of } => one_of
                .iter()
                .map(|p| match p {
                    Pick::Number(x) => vec![num(*x)],
                    Pick::Vector(v) => v.iter().map(|x| num(*x)).collect(),
                })
                .collect(),
        };
        probes.dedup();
        probes
    }

    /// One value drawn from the range, as the texts of its numbers.
    fn draw(&self, rng: &mut Rng) -> Vec<String> {
        let stepped = |lo: f64, hi: f64, step: f64, rng: &mut Rng| {
            let steps = steps(lo, hi, step);
            let k = ((rng.uniform() * (steps as f64 + 1.0)) as u64).min(steps);
            num(lo + k as f64 * step)
        };
        match self {
            Range::Numbers([lo, hi]) => vec![stepped(*lo, *hi, STEP, rng)],
            Range::Stepped { between, step } => vec![stepped(between[0], between[1], *step, rng)],
            Range::Vectors([lo, hi]) => (0..3).map(|i| stepped(lo[i], hi[i], STEP, rng)).collect(),
            Range::OneOf { one_of } => {
                let k = ((rng.uniform() * one_of.len() as f64) as usize).min(one_of.len() - 1);
                match &one_of[k] {
                    Pick::Number(x) => vec![num(*x)],
                    Pick::Vector(v) => v.iter().map(|x| num(*x)).collect(),
                }
            }
        }
    }
}

/// The combinations of probes a validation tries together, for paths with `counts` probes
/// each: per path the index of its probe, or None for the value the lesson writes. Every
/// combination of all the paths where there are at most `limit` (students draw a value for
/// every path), else each pair of paths in every combination of their probes, the others as
/// written. None for a single path: its values are tried alone.
pub fn combinations(counts: &[usize], limit: usize) -> Vec<Vec<Option<usize>>> {
    if counts.len() < 2 {
        return vec![];
    }
    let all = counts
        .iter()
        .try_fold(1usize, |n, &c| n.checked_mul(c))
        .filter(|&n| n <= limit);
    if all.is_some() {
        let mut out: Vec<Vec<Option<usize>>> = vec![vec![]];
        for &c in counts {
            out = out
                .into_iter()
                .flat_map(|head| {
                    (0..c).map(move |k| {
                        let mut picks = head.clone();
                        picks.push(Some(k));
                        picks
                    })
                })
                .collect();
        }
        return out;
    }
    let mut out = Vec::new();
    for a in 0..counts.len() {
        for b in a + 1..counts.len() {
            for i in 0..counts[a] {
                for j in 0..counts[b] {
                    let mut picks = vec![None; counts.len()];
                    (picks[a], picks[b]) = (Some(i), Some(j));
                    out.push(picks);
                }
            }
        }
    }
    out
}

/// A number from a text, stable across platforms and versions (FNV-1a, 64 bits).
fn fnv1a(text: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// The values one student gets: for every varied path, the texts of its numbers.
pub fn draw(
    lesson_id: &str,
    student: &str,
    vary: &BTreeMap<String, Range>,
) -> BTreeMap<String, Vec<String>> {
    vary.iter()
        .map(|(path, range)| {
            let mut rng = Rng::for_pixel(
                fnv1a(&format!("{lesson_id}\u{0}{student}\u{0}{path}")),
                0,
                0,
            );
            (path.clone(), range.draw(&mut rng))
        })
        .collect()
}

/// A value as a student reads it: `0.27`, or `[1, 0, 8.5]`.
pub fn show(values: &[String]) -> String {
    match values {
        [one] => one.clone(),
        many => format!("[{}]", many.join(", ")),
    }
}

/// The scene files' texts with the values written in: for every file (name → text), its new
/// text where a path exists in it. Every path must exist in at least one file.
pub fn rewrite(
    files: &BTreeMap<String, String>,
    values: &BTreeMap<String, Vec<String>>,
) -> Result<BTreeMap<String, String>, String> {
    let mut out = BTreeMap::new();
    let mut used: BTreeMap<&str, bool> = values.keys().map(|p| (p.as_str(), false)).collect();
    for (name, text) in files {
        let root = yaml_spans::parse(text).map_err(|e| format!("{name}: {e}"))?;
        let mut edits: Vec<Edit> = Vec::new();
        for (path, vals) in values {
            if let Some(node) = yaml_spans::find(&root, path) {
                edits.extend(
                    yaml_spans::edits(text, node, vals)
                        .map_err(|e| format!("vary `{path}` in {name}: {e}"))?,
                );
                used.insert(path, true);
            }
        }
        if !edits.is_empty() {
            out.insert(name.clone(), yaml_spans::apply(text, edits));
        }
    }
    if let Some((path, _)) = used.iter().find(|(_, u)| !**u) {
        return Err(format!(
            "vary `{path}`: no scene of the lesson writes that value (write it out to vary it)"
        ));
    }
    Ok(out)
}

/// The values as written in the scene files (the first file that has each path).
pub fn written(
    files: &BTreeMap<String, String>,
    paths: impl Iterator<Item = String>,
) -> BTreeMap<String, String> {
    let parsed: Vec<(&String, yaml_spans::Node)> = files
        .values()
        .filter_map(|text| yaml_spans::parse(text).ok().map(|n| (text, n)))
        .collect();
    paths
        .filter_map(|path| {
            parsed.iter().find_map(|(text, root)| {
                let node = yaml_spans::find(root, &path)?;
                Some((path.clone(), yaml_spans::shown(text, node)?))
            })
        })
        .collect()
}

/// The `{path}` placeholders of a question: braces around a key path (letters, digits, `_`,
/// `-`, `.`), not other braces (`{1, 2}`).
pub fn placeholders(question: &str) -> impl Iterator<Item = &str> {
    question.split('{').skip(1).filter_map(|rest| {
        let (inside, _) = rest.split_once('}')?;
        let path_char = |c: char| c.is_ascii_alphanumeric() || "_-.".contains(c);
        let starts = inside.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_');
        (starts && inside.chars().all(path_char)).then_some(inside)
    })
}

/// A question with `{path}` replaced by the value of each varied path.
pub fn fill(question: &str, values: &BTreeMap<String, String>) -> String {
    let mut q = question.to_string();
    for (path, value) in values {
        q = q.replace(&format!("{{{path}}}"), value);
    }
    q
}

/// The texts of the lesson's scene files: scene.yaml and every scene an exercise names.
pub fn scene_files(
    dir: &Path,
    names: impl Iterator<Item = String>,
) -> Result<BTreeMap<String, String>, LessonError> {
    let mut out = BTreeMap::new();
    for name in std::iter::once("scene.yaml".to_string()).chain(names) {
        if out.contains_key(&name) {
            continue;
        }
        let path = dir.join(&name);
        let text =
            read_text(&path, TEXT_BUDGET).map_err(|e| LessonError::io(&path, "read", e.into()))?;
        out.insert(name, text);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vary(yaml: &str) -> BTreeMap<String, Range> {
        serde_saphyr::from_str(yaml).unwrap()
    }

    #[test]
    fn a_student_always_gets_the_same_values_and_others_get_others() {
        let v = vary("materials.a.kd: [0.1, 0.4]\nobjects.ball.sphere.center: [[-1, 0, 7], [1, 0, 9]]\nambient: { one_of: [0.2, 0.3] }\nlights.L.intensity: { between: [0.8, 1.2], step: 0.05 }\n");
        let alice = draw("03", "alice", &v);
        assert_eq!(alice, draw("03", "alice", &v));
        let kd: f64 = alice["materials.a.kd"][0].parse().unwrap();
        assert!((0.1..=0.4).contains(&kd));
        assert!(((kd * 100.0).round() - kd * 100.0).abs() < 1e-9, "{kd}");
        let i: f64 = alice["lights.L.intensity"][0].parse().unwrap();
        assert!(((i * 20.0).round() - i * 20.0).abs() < 1e-9, "{i}");
        assert_eq!(alice["objects.ball.sphere.center"].len(), 3);
        let students: Vec<_> = (0..20).map(|k| draw("03", &format!("s{k}"), &v)).collect();
        let distinct: std::collections::HashSet<String> =
            students.iter().map(|s| format!("{s:?}")).collect();
        assert!(distinct.len() >= 19, "{} distinct of 20", distinct.len());
    }

    /// A step finer than the values are written with is refused (students would all get lo,
    /// or values off the step's grid); a range of more steps than u64 counts draws without
    /// overflowing.
    #[test]
    fn a_step_finer_than_six_decimals_is_refused_and_huge_ranges_draw() {
        let v = vary("a: { between: [0.1, 0.2], step: 1e-21 }\nb: { between: [0.1, 0.2], step: 1e-6 }\nc: { between: [-1e300, 1e300], step: 1 }\nd: { between: [-1e300, 1e300], step: 1e299 }\n");
        assert_eq!(v["a"].check(), Err(RangeError::StepTooFine));
        assert_eq!(v["b"].check(), Ok(()));
        assert_eq!(
            v["c"].check(),
            Err(RangeError::StepTooFine),
            "1 is lost in 1e300"
        );
        assert_eq!(v["d"].check(), Ok(()));
        let drawn: std::collections::BTreeSet<String> = (0..40)
            .map(|k| draw("03", &format!("s{k}"), &v)["d"][0].clone())
            .collect();
        assert!(drawn.len() > 10, "{drawn:?}");
    }

    /// A value that is no range is refused with the forms a range takes, not serde's words.
    #[test]
    fn a_value_that_is_no_range_is_refused_with_the_forms_of_a_range() {
        let e = serde_saphyr::from_str::<BTreeMap<String, Range>>("ambient: [1, \"x\"]\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("a range: [lo, hi]"), "{e}");
        assert!(!e.contains("untagged"), "{e}");
    }

    /// A validation tries the values students draw: lo + k·step up to the last step within
    /// the range (180 of 40 to 200 in steps of 70), never the range's end where no step lands.
    #[test]
    fn the_probes_are_the_ends_of_what_is_drawn() {
        let v = vary("camera.fov: { between: [40, 200], step: 70 }\nambient: [0.1, 0.4]\n");
        assert_eq!(v["camera.fov"].probes(), [["40"], ["110"], ["180"]]);
        assert_eq!(v["ambient"].probes(), [["0.1"], ["0.11"], ["0.4"]]);
        let drawn: std::collections::BTreeSet<String> = (0..200)
            .map(|k| draw("03", &format!("s{k}"), &v)["camera.fov"][0].clone())
            .collect();
        assert_eq!(drawn, ["110", "180", "40"].map(String::from).into());
    }

    /// Every combination of all the paths while there are few (3 × 2 × 2 = 12, each once),
    /// else every pair of paths in all their combinations (3 paths of 3: 3 pairs × 9).
    #[test]
    fn combinations_are_all_of_them_or_every_pair() {
        let all = combinations(&[3, 2, 2], 12);
        assert_eq!(all.len(), 12);
        let distinct: std::collections::BTreeSet<_> = all.iter().collect();
        assert_eq!(distinct.len(), 12);
        assert!(all.iter().all(|p| p.iter().all(Option::is_some)));
        assert!(all.contains(&vec![Some(2), Some(1), Some(0)]));
        let pairs = combinations(&[3, 3, 3], 26);
        assert_eq!(pairs.len(), 27);
        assert!(pairs.iter().all(|p| p.iter().flatten().count() == 2));
        assert!(pairs.contains(&vec![Some(2), None, Some(0)]));
        assert!(combinations(&[3], 100).is_empty());
    }

    #[test]
    fn placeholders_are_key_paths_in_braces() {
        let q = "kd {materials.a.kd}, ambient {ambient}, the set {1, 2}, {x y}, {}";
        assert_eq!(
            placeholders(q).collect::<Vec<_>>(),
            ["materials.a.kd", "ambient"]
        );
    }

    #[test]
    fn every_path_must_exist_somewhere() {
        let files: BTreeMap<String, String> =
            [("scene.yaml".to_string(), "ambient: 0.3\n".to_string())].into();
        let values: BTreeMap<String, Vec<String>> =
            [("ambient".to_string(), vec!["0.25".to_string()])].into();
        assert_eq!(
            rewrite(&files, &values).unwrap()["scene.yaml"],
            "ambient: 0.25\n"
        );
        let missing: BTreeMap<String, Vec<String>> =
            [("materials.a.kd".to_string(), vec!["1".to_string()])].into();
        assert!(rewrite(&files, &missing)
            .unwrap_err()
            .contains("materials.a.kd"));
    }
}
