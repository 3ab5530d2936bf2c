//! Checking options: every problem of an options struct at once, before any work.

use std::fmt;

/// One option outside its allowed values.
#[derive(Debug, Clone, PartialEq)]
pub struct OptionProblem {
    /// The option's name (`head_slice_step`, `ears.reach`).
    pub name: String,
    /// The value given.
    pub value: f64,
    /// The allowed values.
    pub range: String,
}

impl fmt::Display for OptionProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} = {} is out of range {}",
            self.name, self.value, self.range
        )
    }
}

/// Every problem of one options struct (never empty).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}", list(.0))]
pub struct OptionProblems(pub Vec<OptionProblem>);

fn list(problems: &[OptionProblem]) -> String {
    problems
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ")
}

/// Collects option problems; [`Checks::finish`] turns them into a result.
#[derive(Debug, Default)]
pub struct Checks(Vec<OptionProblem>);

impl Checks {
    /// `v` must be finite and within `[lo, hi]`.
    pub fn range(&mut self, name: &str, v: f64, lo: f64, hi: f64) {
        if !(v.is_finite() && v >= lo && v <= hi) {
            self.push(name, v, format!("[{lo}, {hi}]"));
        }
    }

    /// `v` must be finite, above zero and at most `hi` (a step or size: zero would not advance).
    pub fn positive(&mut self, name: &str, v: f64, hi: f64) {
        if !(v.is_finite() && v > 0.0 && v <= hi) {
            self.push(name, v, format!("(0, {hi}]"));
        }
    }

    /// `v` must be at least `lo`.
    pub fn at_least(&mut self, name: &str, v: usize, lo: usize) {
        if v < lo {
            self.push(name, v as f64, format!("{lo} or more"));
        }
    }

    /// The problems of a nested options struct, their names prefixed with `prefix.`.
    pub fn nested(&mut self, prefix: &str, checked: Result<(), OptionProblems>) {
        if let Err(OptionProblems(problems)) = checked {
            self.0.extend(problems.into_iter().map(|p| OptionProblem {
                name: format!("{prefix}.{}", p.name),
                ..p
            }));
        }
    }

    fn push(&mut self, name: &str, value: f64, range: String) {
        self.0.push(OptionProblem {
            name: name.to_string(),
            value,
            range,
        });
    }

    /// `Ok` when nothing was found.
    ///
    /// # Errors
    /// Every problem found.
    pub fn finish(self) -> Result<(), OptionProblems> {
        if self.0.is_empty() {
            Ok(())
        } else {
            Err(OptionProblems(self.0))
        }
    }
}
