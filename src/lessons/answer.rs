//! Answers: what a student types, and comparing it with what raytree computes.

use glam::DVec3;

use super::error::AnswerError;
use super::tolerance::Tolerance;

/// An answer to an exercise, a student's or raytree's.
#[derive(Clone, Debug, PartialEq)]
pub enum Answer {
    /// A number: a t, a count, a factor, or a grey intensity.
    Number(f64),
    /// A point, a direction, barycentric coordinates, or an r, g, b intensity.
    Vector(DVec3),
    /// A segment list [(t_in, t_out), ...]; empty for a miss.
    Segments(Vec<(f64, f64)>),
    /// Total internal reflection: no refracted direction.
    Tir,
    /// Numbers in a count no answer has (two, four, or an odd count for a segment list): they
    /// read, but match nothing.
    Numbers(Vec<f64>),
}

impl Answer {
    /// A colour: one number when grey.
    pub fn color(c: DVec3) -> Answer {
        if c.x == c.y && c.y == c.z {
            Answer::Number(c.x)
        } else {
            Answer::Vector(c)
        }
    }

    /// The answer as `check` prints it and a student may type it: numbers with at most six
    /// decimals, `x, y, z`, `a, b; c, d` for a segment list (`none` when empty), or `tir`.
    pub fn show(&self) -> String {
        // Six decimals, but a number below 10⁻³ keeps six significant digits: 1.1·10⁻⁶ shown
        // as 0.000001 would seem to lie within a tolerance of 10⁻⁶ it misses.
        let num = |x: f64| {
            if x != 0.0 && x.abs() < 1e-3 {
                crate::trace::text::scientific(x)
            } else {
                crate::trace::text::num(x)
            }
        };
        match self {
            Answer::Number(x) => num(*x),
            Answer::Vector(v) => format!("{}, {}, {}", num(v.x), num(v.y), num(v.z)),
            Answer::Segments(s) if s.is_empty() => "none".into(),
            Answer::Segments(s) => s
                .iter()
                .map(|(a, b)| format!("{}, {}", num(*a), num(*b)))
                .collect::<Vec<_>>()
                .join("; "),
            Answer::Tir => "tir".into(),
            Answer::Numbers(v) => v.iter().map(|x| num(*x)).collect::<Vec<_>>().join(", "),
        }
    }

    /// The answer as JSON: a number, [x, y, z], [[t_in, t_out], ...], or "tir".
    pub fn to_json(&self) -> serde_json::Value {
        use serde_json::json;
        let t = |x: f64| {
            if x.is_finite() {
                json!(x)
            } else {
                json!(crate::trace::text::num(x))
            }
        };
        match self {
            Answer::Number(x) => t(*x),
            Answer::Vector(v) => json!([t(v.x), t(v.y), t(v.z)]),
            Answer::Segments(s) => json!(s
                .iter()
                .map(|(a, b)| json!([t(*a), t(*b)]))
                .collect::<Vec<_>>()),
            Answer::Tir => json!("tir"),
            Answer::Numbers(v) => json!(v.iter().map(|x| t(*x)).collect::<Vec<_>>()),
        }
    }

    /// The room `tol` leaves around this (expected) answer: for its largest number.
    pub fn allowance(&self, tol: &Tolerance) -> f64 {
        let largest = match self {
            Answer::Number(x) => x.abs(),
            Answer::Vector(v) => v.abs().max_element(),
            Answer::Segments(s) => s
                .iter()
                .flat_map(|(a, b)| [a.abs(), b.abs()])
                .filter(|x| x.is_finite())
                .fold(0.0, f64::max),
            Answer::Tir => 0.0,
            Answer::Numbers(v) => v.iter().map(|x| x.abs()).fold(0.0, f64::max),
        };
        tol.around(largest)
    }

    /// Within the tolerance of `expected`, component by component, each allowed
    /// `tol.around(scale)`: the scale is the expected number itself, or the largest component
    /// of an expected vector. A single number matches a grey colour.
    pub fn matches(&self, expected: &Answer, tol: &Tolerance) -> bool {
        let close = |a: f64, b: f64, scale: f64| {
            (a - b).abs() <= tol.around(scale) || (a.is_infinite() && a == b)
        };
        let largest = |v: &DVec3| v.abs().max_element();
        match (self, expected) {
            (Answer::Number(a), Answer::Number(b)) => close(*a, *b, *b),
            (Answer::Vector(a), Answer::Vector(b)) => (0..3).all(|i| close(a[i], b[i], largest(b))),
            (Answer::Number(a), Answer::Vector(b)) => (0..3).all(|i| close(*a, b[i], largest(b))),
            (Answer::Vector(a), Answer::Number(b)) => (0..3).all(|i| close(a[i], *b, *b)),
            (Answer::Segments(a), Answer::Segments(b)) => {
                a.len() == b.len()
                    && a.iter()
                        .zip(b)
                        .all(|(x, y)| close(x.0, y.0, y.0) && close(x.1, y.1, y.1))
            }
            (Answer::Tir, Answer::Tir) => true,
            _ => false,
        }
    }
}

/// A number as a student writes it: `0.25`, `-3`, a fraction `1/3` (one slash: `1/2/3` could
/// be read two ways, and is refused); `inf` and `∞` where infinite values are answers (the
/// open ends of segment lists). A number too large for a double (`1e999`, a page of digits) is
/// refused, not read as ∞.
fn number(s: &str, infinite_allowed: bool) -> Result<f64, AnswerError> {
    let s = s.trim();
    let shown = || {
        let short: String = s.chars().take(24).collect();
        if short.len() < s.len() {
            format!("{short}…")
        } else {
            short
        }
    };
    let value = match s.split_once('/') {
        Some((_, b)) if b.contains('/') => return Err(AnswerError::NotANumber(shown())),
        Some((a, b)) => number(a, false)? / number(b, false)?,
        None => match s.to_ascii_lowercase().as_str() {
            "inf" | "∞" | "+inf" | "+∞" | "-inf" | "-∞" | "−∞" | "−inf" => {
                if !infinite_allowed {
                    return Err(AnswerError::Infinite(s.into()));
                }
                if s.starts_with(['-', '−']) {
                    f64::NEG_INFINITY
                } else {
                    f64::INFINITY
                }
            }
            _ => s
                .replace('−', "-")
                .parse::<f64>()
                .map_err(|_| AnswerError::NotANumber(shown()))?,
        },
    };
    if value.is_nan() {
        return Err(AnswerError::NotANumber(shown()));
    }
    let sign_less = s.trim_start_matches(['+', '-', '−']).to_ascii_lowercase();
    if value.is_infinite() && !matches!(sign_less.as_str(), "inf" | "∞") {
        return Err(AnswerError::TooLarge(shown()));
    }
    Ok(value)
}

/// Parses an answer: `tir` (or `total internal reflection`), `none` (an empty segment list, whatever is asked), a number, `x, y, z`, or a segment
/// list `a, b; c, d` (brackets and parentheses are ignored). An answer without a number in it
/// (empty, or punctuation alone) is refused: an empty segment list is written `none`.
pub fn parse_answer(s: &str, segments: bool) -> Result<Answer, AnswerError> {
    // Words in any case; the numbers as typed, so that an error quotes them so.
    let t = s.trim();
    let word = t.to_ascii_lowercase();
    // Total internal reflection, as a student names it: `tir`, or the words themselves.
    let words: Vec<&str> = word.split_whitespace().collect();
    if word == "tir" || words == ["total", "internal", "reflection"] {
        return Ok(Answer::Tir);
    }
    // An empty segment list, whatever is asked: where something else is, it is an answer of
    // the wrong kind (wrong), not text that does not read.
    if matches!(word.as_str(), "none" | "empty") {
        return Ok(Answer::Segments(vec![]));
    }
    let cleaned: String = t
        .chars()
        .map(|c| if "()[]{}".contains(c) { ' ' } else { c })
        .collect();
    // A fraction may be written with spaces round its slash: `1 / 2`.
    let cleaned = cleaned
        .split('/')
        .map(str::trim)
        .collect::<Vec<_>>()
        .join("/");
    let parts: Vec<f64> = cleaned
        .split([',', ';', ' '])
        .filter(|p| !p.trim().is_empty())
        .map(|p| number(p, segments))
        .collect::<Result<_, _>>()?;
    if parts.is_empty() && s.trim().is_empty() {
        return Err(AnswerError::Empty(if segments {
            "pairs t_in, t_out (e.g. `13, 16; 22, 23`), or `none` for an empty list"
        } else {
            "a number, or three (x, y, z)"
        }));
    }
    if parts.is_empty() {
        return Err(if segments {
            AnswerError::NoSegments(s.trim().into())
        } else {
            AnswerError::NoNumbers(s.trim().into())
        });
    }
    if segments {
        if !parts.len().is_multiple_of(2) {
            return Ok(Answer::Numbers(parts));
        }
        return Ok(Answer::Segments(
            parts.chunks(2).map(|p| (p[0], p[1])).collect(),
        ));
    }
    Ok(match parts.as_slice() {
        [x] => Answer::Number(*x),
        [x, y, z] => Answer::Vector(DVec3::new(*x, *y, *z)),
        _ => Answer::Numbers(parts),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small answer keeps its digits where six decimals would round it onto the tolerance
    /// it misses; others show six decimals as before.
    #[test]
    fn small_numbers_show_their_own_digits() {
        assert_eq!(Answer::Number(1.1e-6).show(), "1.1e-6");
        assert_eq!(Answer::Number(0.0).show(), "0");
        assert_eq!(Answer::Number(0.185764).show(), "0.185764");
        assert_eq!(
            Answer::Vector(glam::DVec3::new(0.6, -0.00025, 0.0)).show(),
            "0.6, -2.5e-4, 0"
        );
    }

    /// A colour is one number only when all three channels are equal; two equal channels
    /// and a third different (either side) is a colour.
    #[test]
    fn a_colour_is_one_number_only_when_grey() {
        assert_eq!(Answer::color(DVec3::splat(0.5)), Answer::Number(0.5));
        for c in [
            DVec3::new(0.5, 0.5, 0.3),
            DVec3::new(0.3, 0.5, 0.5),
            DVec3::new(0.5, 0.3, 0.5),
        ] {
            assert_eq!(Answer::color(c), Answer::Vector(c));
        }
    }

    /// An empty answer says that nothing was given, not that "``" holds no numbers.
    #[test]
    fn an_empty_answer_says_none_was_given() {
        for segments in [false, true] {
            for empty in ["", "   "] {
                let e = parse_answer(empty, segments).unwrap_err().to_string();
                assert!(e.starts_with("no answer given: give "), "{e}");
            }
        }
        assert!(matches!(
            parse_answer(" ; ", false),
            Err(AnswerError::NoNumbers(_))
        ));
    }

    /// Total internal reflection is `tir` or its name in words, in any case and spacing.
    #[test]
    fn total_internal_reflection_is_named_in_words_too() {
        for said in [
            "tir",
            " TIR ",
            "total internal reflection",
            "Total  Internal Reflection",
        ] {
            assert_eq!(parse_answer(said, false).unwrap(), Answer::Tir, "{said}");
        }
        assert!(parse_answer("total reflection", false).is_err());
    }

    #[test]
    fn parses_what_students_write() {
        assert_eq!(parse_answer(" 0.25 ", false).unwrap(), Answer::Number(0.25));
        assert_eq!(
            parse_answer("(0.6, -0.8, 0)", false).unwrap(),
            Answer::Vector(DVec3::new(0.6, -0.8, 0.0))
        );
        assert_eq!(parse_answer("1/4", false).unwrap(), Answer::Number(0.25));
        assert_eq!(parse_answer("TIR", false).unwrap(), Answer::Tir);
        assert_eq!(parse_answer("1E-1", false).unwrap(), Answer::Number(0.1));
        assert_eq!(
            parse_answer("0, INF", true).unwrap(),
            Answer::Segments(vec![(0.0, f64::INFINITY)])
        );
        // A part that is no number is quoted as typed.
        assert_eq!(
            parse_answer("ABC", false),
            Err(AnswerError::NotANumber("ABC".into()))
        );
        assert_eq!(
            parse_answer("I = 0.87", false),
            Err(AnswerError::NotANumber("I".into()))
        );
        assert_eq!(
            parse_answer("13, 16; 22, 23", true).unwrap(),
            Answer::Segments(vec![(13.0, 16.0), (22.0, 23.0)])
        );
        assert_eq!(
            parse_answer("[13, 16] [22, 23]", true).unwrap(),
            Answer::Segments(vec![(13.0, 16.0), (22.0, 23.0)])
        );
        assert_eq!(
            parse_answer("none", true).unwrap(),
            Answer::Segments(vec![])
        );
        assert!(parse_answer("abc", false).is_err());
        // A fraction's slash may have spaces round it.
        assert_eq!(parse_answer("1 / 4", false).unwrap(), Answer::Number(0.25));
        assert_eq!(
            parse_answer("1/2, 0, -3 / 4", false).unwrap(),
            Answer::Vector(DVec3::new(0.5, 0.0, -0.75))
        );
        // Numbers in a count no answer has read, as numbers that match nothing.
        assert_eq!(
            parse_answer("1, 2", false).unwrap(),
            Answer::Numbers(vec![1.0, 2.0])
        );
        assert_eq!(
            parse_answer("13, 16, 22", true).unwrap(),
            Answer::Numbers(vec![13.0, 16.0, 22.0])
        );
        assert_eq!(
            parse_answer("(-inf, 16); [22, ∞)", true).unwrap(),
            Answer::Segments(vec![(f64::NEG_INFINITY, 16.0), (22.0, f64::INFINITY)])
        );
    }

    /// Punctuation, emptiness and numbers too large for a double are not answers.
    #[test]
    fn refuses_what_is_not_an_answer() {
        let digits = "9".repeat(10_000);
        for segments in [false, true] {
            for s in [
                ",",
                ";",
                " ; ",
                "",
                "  ",
                "[]",
                "()",
                "1e999",
                "-1e999",
                digits.as_str(),
            ] {
                let e = parse_answer(s, segments);
                assert!(e.is_err(), "`{s}` (segments: {segments}) accepted as {e:?}");
            }
        }
        for s in ["inf", "∞", "-inf", "1/0"] {
            assert!(
                parse_answer(s, false).is_err(),
                "`{s}` accepted as a number"
            );
        }
        let e = parse_answer(&digits, false).unwrap_err();
        assert!(
            matches!(&e, AnswerError::TooLarge(shown) if shown.ends_with('…')),
            "{e:?}"
        );
        assert!(e.to_string().len() < 100, "{e}");
        // (1/2)/3 or 1/(2/3): two readings, so neither.
        assert_eq!(
            parse_answer("1/2/3", false),
            Err(AnswerError::NotANumber("1/2/3".into()))
        );
        let numbers = Answer::Numbers(vec![1.0, 2.0]);
        assert!(!numbers.matches(&numbers, &Tolerance::default()));
    }

    /// The JSON forms `check --format json` prints: a number, [x, y, z], a list of [t_in, t_out]
    /// with an open end written "∞", and "tir".
    #[test]
    fn answers_as_json() {
        use serde_json::json;
        assert_eq!(Answer::Number(0.25).to_json(), json!(0.25));
        assert_eq!(
            Answer::Vector(DVec3::new(0.6, -0.8, 0.0)).to_json(),
            json!([0.6, -0.8, 0.0])
        );
        assert_eq!(
            Answer::Segments(vec![(2.0, 4.0), (10.0, f64::INFINITY)]).to_json(),
            json!([[2.0, 4.0], [10.0, "∞"]])
        );
        assert_eq!(Answer::Segments(vec![]).to_json(), json!([]));
        assert_eq!(Answer::Tir.to_json(), json!("tir"));
    }

    /// The room printed beside an answer (`check --format json`'s `tolerance`): ±0.1 % of the
    /// largest finite number, at least 1e-6.
    #[test]
    fn the_allowance_is_taken_on_the_largest_finite_number() {
        let tol = Tolerance::default();
        let close = |a: f64, b: f64| (a - b).abs() < 1e-15;
        assert!(close(Answer::Number(-0.5).allowance(&tol), 0.5e-3));
        assert!(close(Answer::Number(1e-4).allowance(&tol), 1e-6));
        let v = Answer::Vector(DVec3::new(1.0, -3.0, 2.0));
        assert!(close(v.allowance(&tol), 3e-3));
        let s = Answer::Segments(vec![(2.0, 4.0), (10.0, f64::INFINITY)]);
        assert!(close(s.allowance(&tol), 10e-3));
        assert!(close(Answer::Tir.allowance(&tol), 1e-6));
    }

    /// Each end of each segment is held to the tolerance around itself: half of it off is
    /// accepted, twice off is refused, and so is a list with a segment missing or added.
    #[test]
    fn segment_lists_are_held_to_the_tolerance_end_by_end() {
        let expected = Answer::Segments(vec![(2.0, 4.0), (10.0, f64::INFINITY)]);
        let tol = Tolerance::default();
        for (end, scale) in [(0, 2.0), (1, 4.0), (2, 10.0)] {
            let shifted = |by: f64| {
                let mut ends = [2.0, 4.0, 10.0];
                ends[end] += by * tol.around(scale);
                Answer::Segments(vec![(ends[0], ends[1]), (ends[2], f64::INFINITY)])
            };
            assert!(shifted(0.5).matches(&expected, &tol), "end {end}");
            assert!(shifted(-0.5).matches(&expected, &tol), "end {end}");
            assert!(!shifted(2.0).matches(&expected, &tol), "end {end}");
            assert!(!shifted(-2.0).matches(&expected, &tol), "end {end}");
        }
        assert!(!Answer::Segments(vec![(2.0, 4.0)]).matches(&expected, &tol));
        let three = Answer::Segments(vec![(2.0, 4.0), (10.0, f64::INFINITY), (20.0, 30.0)]);
        assert!(!three.matches(&expected, &tol));
        let finite = Answer::Segments(vec![(2.0, 4.0), (10.0, 1e300)]);
        assert!(!finite.matches(&expected, &tol));
        let open = Answer::Segments(vec![(2.0, 4.0), (10.0, f64::INFINITY)]);
        let closed = Answer::Segments(vec![(2.0, 4.0), (10.0, 12.0)]);
        assert!(!open.matches(&closed, &tol), "an open end for a closed one");
    }

    #[test]
    fn tolerance_is_per_component_on_the_vector_scale() {
        let a = Answer::Vector(DVec3::new(1.0, 2.0, 3.0));
        let tol = Tolerance::absolute(1e-3);
        assert!(Answer::Vector(DVec3::new(1.0009, 2.0, 3.0)).matches(&a, &tol));
        assert!(!Answer::Vector(DVec3::new(1.0011, 2.0, 3.0)).matches(&a, &tol));
        // 0.1% of the largest component, 3: 0.003 on each.
        let rel = Tolerance::default();
        assert!(Answer::Vector(DVec3::new(1.0029, 2.0, 3.0)).matches(&a, &rel));
        assert!(!Answer::Vector(DVec3::new(1.0031, 2.0, 3.0)).matches(&a, &rel));
        assert!(Answer::Number(0.5).matches(&Answer::Vector(DVec3::splat(0.5)), &rel));
    }
}
