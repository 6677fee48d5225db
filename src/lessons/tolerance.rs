//! How close an answer must be: a relative tolerance with an absolute floor. An answer `a` to
//! an expected value `e` is right when |a − e| ≤ max(relative·|e|, absolute), so a small value
//! (a Phong highlight of 0.0038) is held to its own scale, and a value of zero still has room
//! for rounding. In `exercises.yaml`:
//!
//! ```yaml
//! tolerance: { relative: 1e-3, absolute: 1e-6 }   # the default
//! tolerance: 0.018                                 # a plain number: absolute only
//! tolerance: { standard_errors: 4 }                # a Monte Carlo mean: 4 of its standard errors
//! ```
//!
//! The last form is for a node that is the mean of n sampled rays (a glossy or frosted cone):
//! raytree's estimate is itself noisy, so the answer (the value the estimate converges to) is
//! right within k standard errors s/√n of raytree's mean, s the spread of the n rays' values.
//!
//! A vector (a direction, a point, a colour) is measured on the scale of its largest
//! component, so a component that happens to be near zero is not held to a tighter standard
//! than the vector as a whole.

use serde::{Deserialize, Serialize};

use crate::trace::text::num;

/// How close an answer must be to the expected value: right when |a − e| ≤ max(relative·|e|,
/// absolute).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Tolerance {
    /// Allowance as a fraction of the expected value's size.
    pub relative: f64,
    /// The smallest allowance, for values near zero.
    pub absolute: f64,
    /// k for a Monte Carlo mean: the allowance is at least k standard errors of the mean
    /// (`with_standard_error` fills it into `absolute`); 0 otherwise.
    #[serde(skip_serializing_if = "is_zero")]
    pub standard_errors: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl Default for Tolerance {
    fn default() -> Tolerance {
        Tolerance {
            relative: 1e-3,
            absolute: 1e-6,
            standard_errors: 0.0,
        }
    }
}

impl Tolerance {
    /// Only an absolute allowance: |a − e| ≤ `absolute`.
    pub fn absolute(absolute: f64) -> Tolerance {
        Tolerance {
            relative: 0.0,
            absolute,
            standard_errors: 0.0,
        }
    }

    /// The rule for a mean whose standard error is `se`: at least k·se.
    pub fn with_standard_error(self, se: f64) -> Tolerance {
        Tolerance {
            absolute: self.absolute.max(self.standard_errors * se),
            ..self
        }
    }

    /// The allowance around a value of size `scale`: max(relative·|scale|, absolute).
    pub fn around(&self, scale: f64) -> f64 {
        let r = self.relative * scale.abs();
        if r.is_finite() {
            r.max(self.absolute)
        } else {
            self.absolute
        }
    }

    /// The rule in words, as `check` prints it: "±0.1% (at least 0.000001)" or "±0.018".
    pub fn describe(&self) -> String {
        if self.standard_errors > 0.0 {
            return match self.absolute > 0.0 {
                true => format!(
                    "±{} ({} standard errors of raytree's mean)",
                    sci(self.absolute),
                    num(self.standard_errors)
                ),
                false => format!(
                    "±{} standard errors of raytree's mean",
                    num(self.standard_errors)
                ),
            };
        }
        match (self.relative > 0.0, self.absolute > 0.0) {
            (true, true) => format!(
                "±{}% (at least {})",
                num(self.relative * 100.0),
                sci(self.absolute)
            ),
            (true, false) => format!("±{}%", num(self.relative * 100.0)),
            (false, _) => format!("±{}", sci(self.absolute)),
        }
    }
}

/// A small number without losing it to six decimals (1e-9 would print as 0).
fn sci(x: f64) -> String {
    if x != 0.0 && x.abs() < 1e-4 {
        format!("{x:e}")
    } else {
        num(x)
    }
}

/// The file's forms: a plain number (absolute), or `{ relative, absolute }`.
#[derive(Deserialize)]
#[serde(untagged)]
enum Form {
    Absolute(f64),
    Rule {
        relative: Option<f64>,
        absolute: Option<f64>,
        standard_errors: Option<f64>,
    },
}

impl<'de> Deserialize<'de> for Tolerance {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Tolerance, D::Error> {
        use serde::de::Error;
        let t = match Form::deserialize(d)? {
            Form::Absolute(a) => Tolerance::absolute(a),
            Form::Rule {
                relative,
                absolute,
                standard_errors,
            } => {
                let default = Tolerance::default();
                Tolerance {
                    relative: relative.unwrap_or(0.0),
                    absolute: absolute.unwrap_or(if relative.is_some() {
                        default.absolute
                    } else {
                        0.0
                    }),
                    standard_errors: standard_errors.unwrap_or(0.0),
                }
            }
        };
        let ok = |x: f64| x.is_finite() && x >= 0.0;
        if !ok(t.relative)
            || !ok(t.absolute)
            || !ok(t.standard_errors)
            || (t.relative == 0.0 && t.absolute == 0.0 && t.standard_errors == 0.0)
        {
            return Err(D::Error::custom(
                "a tolerance is a positive number, or { relative: r, absolute: a, standard_errors: k } with r, a, k ≥ 0 and not all 0",
            ));
        }
        Ok(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_floor_holds_near_zero_and_the_scale_holds_above() {
        let t = Tolerance::default();
        assert_eq!(t.around(0.0), 1e-6);
        assert!((t.around(0.003839) - 3.839e-6).abs() < 1e-15);
        assert!((t.around(-13.0) - 0.013).abs() < 1e-15);
        assert_eq!(Tolerance::absolute(0.018).around(5.0), 0.018);
    }

    #[test]
    fn both_forms_read() {
        let read = |s: &str| serde_saphyr::from_str::<Tolerance>(s);
        assert_eq!(read("0.018").unwrap(), Tolerance::absolute(0.018));
        assert_eq!(
            read("{ relative: 0.01 }").unwrap(),
            Tolerance {
                relative: 0.01,
                absolute: 1e-6,
                standard_errors: 0.0
            }
        );
        assert_eq!(
            read("{ relative: 0.01, absolute: 0.5 }").unwrap(),
            Tolerance {
                relative: 0.01,
                absolute: 0.5,
                standard_errors: 0.0
            }
        );
        let mc = read("{ standard_errors: 4 }").unwrap();
        assert_eq!(
            (mc.relative, mc.absolute, mc.standard_errors),
            (0.0, 0.0, 4.0)
        );
        assert_eq!(mc.with_standard_error(0.05).around(0.3), 0.2);
        assert_eq!(mc.describe(), "±4 standard errors of raytree's mean");
        assert!(read("-1").is_err());
        assert!(read("{ relative: 0, absolute: 0 }").is_err());
    }

    #[test]
    fn described_as_printed() {
        assert_eq!(Tolerance::default().describe(), "±0.1% (at least 1e-6)");
        assert_eq!(Tolerance::absolute(0.018).describe(), "±0.018");
    }
}
