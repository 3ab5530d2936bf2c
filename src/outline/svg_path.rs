//! Flattening SVG path data (`d` attribute) into a polyline.

use super::OutlineError;
use glam::DVec2;

/// The numbers in an SVG number list (`1,2 -3.5e2 .5.5`).
pub(crate) fn numbers(text: &str) -> Result<Vec<f64>, String> {
    let mut tokens = Tokens::new(text);
    let mut out = Vec::new();
    while tokens.skip_separators() {
        out.push(tokens.number()?);
    }
    Ok(out)
}

/// Flattens path data `d` into points (SVG frame, y down). Curves become `segments` lines each.
/// One subpath only; `Z` ends it.
pub(crate) fn flatten(d: &str, segments: usize) -> Result<Vec<DVec2>, OutlineError> {
    let err = |index: usize, message: String| OutlineError::Parse {
        location: format!("path command {}", index + 1),
        message,
    };
    let mut tokens = Tokens::new(d);
    let mut pen = Pen {
        segments: segments.max(1),
        ..Pen::default()
    };
    let mut command: Option<char> = None;
    let mut index = 0usize;
    while tokens.skip_separators() {
        if pen.closed {
            return Err(err(
                index,
                "a second subpath after 'Z': give one closed outline per file".into(),
            ));
        }
        let c = match tokens.command() {
            Some(c) => {
                index += 1;
                c
            }
            None => match command {
                // Implicit repetition; a repeated moveto is a lineto.
                Some('M') => 'L',
                Some('m') => 'l',
                Some(c) => c,
                None => return Err(err(index, "path data must start with a moveto 'M'".into())),
            },
        };
        if pen.points.is_empty() && !c.eq_ignore_ascii_case(&'M') {
            return Err(err(index, "path data must start with a moveto 'M'".into()));
        }
        command = Some(c);
        let count = match c.to_ascii_uppercase() {
            'M' if !pen.points.is_empty() => {
                return Err(err(
                    index,
                    "a second subpath: give one closed outline per file".into(),
                ))
            }
            'M' | 'L' | 'T' => 2,
            'H' | 'V' => 1,
            'C' => 6,
            'S' | 'Q' => 4,
            'Z' => 0,
            'A' => {
                return Err(err(
                    index,
                    "elliptical arcs ('A') are not supported: convert arcs to curves".into(),
                ))
            }
            other => return Err(err(index, format!("unknown path command '{other}'"))),
        };
        let v = (0..count)
            .map(|_| {
                tokens.skip_separators();
                tokens.number().map_err(|m| err(index, m))
            })
            .collect::<Result<Vec<f64>, OutlineError>>()?;
        pen.draw(c, &v);
        if c.eq_ignore_ascii_case(&'Z') {
            command = None;
        }
    }
    if pen.points.is_empty() {
        return Err(err(0, "the path is empty".into()));
    }
    Ok(pen.points)
}

/// The state of [`flatten`] between path commands.
#[derive(Default)]
struct Pen {
    /// Lines per curve.
    segments: usize,
    /// The points so far.
    points: Vec<DVec2>,
    /// The current point.
    current: DVec2,
    /// The subpath's start.
    start: DVec2,
    /// The last curve's kind (`C` or `Q`) and second control point, for `S` and `T`.
    last_control: Option<(char, DVec2)>,
    /// Whether `Z` closed the subpath.
    closed: bool,
}

impl Pen {
    /// Applies command `c` (any case; not `A`) with its numbers `v`.
    fn draw(&mut self, c: char, v: &[f64]) {
        let relative = c.is_ascii_lowercase();
        let base = if relative { self.current } else { DVec2::ZERO };
        let current = self.current;
        match c.to_ascii_uppercase() {
            'M' => {
                self.current = base + DVec2::new(v[0], v[1]);
                self.start = self.current;
                self.points.push(self.current);
                self.last_control = None;
            }
            'L' => {
                self.current = base + DVec2::new(v[0], v[1]);
                self.points.push(self.current);
                self.last_control = None;
            }
            'H' => {
                self.current.x = if relative { current.x + v[0] } else { v[0] };
                self.points.push(self.current);
                self.last_control = None;
            }
            'V' => {
                self.current.y = if relative { current.y + v[0] } else { v[0] };
                self.points.push(self.current);
                self.last_control = None;
            }
            'C' | 'S' => {
                let (c1, c2, end) = if c.eq_ignore_ascii_case(&'C') {
                    (
                        base + DVec2::new(v[0], v[1]),
                        base + DVec2::new(v[2], v[3]),
                        base + DVec2::new(v[4], v[5]),
                    )
                } else {
                    let c1 = match self.last_control {
                        Some(('C', p)) => 2.0 * current - p,
                        _ => current,
                    };
                    (
                        c1,
                        base + DVec2::new(v[0], v[1]),
                        base + DVec2::new(v[2], v[3]),
                    )
                };
                let p0 = current;
                for k in 1..=self.segments {
                    let t = k as f64 / self.segments as f64;
                    let u = 1.0 - t;
                    self.points.push(
                        u * u * u * p0
                            + 3.0 * u * u * t * c1
                            + 3.0 * u * t * t * c2
                            + t * t * t * end,
                    );
                }
                self.current = end;
                self.last_control = Some(('C', c2));
            }
            'Q' | 'T' => {
                let (c1, end) = if c.eq_ignore_ascii_case(&'Q') {
                    (base + DVec2::new(v[0], v[1]), base + DVec2::new(v[2], v[3]))
                } else {
                    let c1 = match self.last_control {
                        Some(('Q', p)) => 2.0 * current - p,
                        _ => current,
                    };
                    (c1, base + DVec2::new(v[0], v[1]))
                };
                let p0 = current;
                for k in 1..=self.segments {
                    let t = k as f64 / self.segments as f64;
                    let u = 1.0 - t;
                    self.points
                        .push(u * u * p0 + 2.0 * u * t * c1 + t * t * end);
                }
                self.current = end;
                self.last_control = Some(('Q', c1));
            }
            _ => {
                // 'Z'
                if self.points.last() != Some(&self.start) {
                    self.points.push(self.start);
                }
                self.current = self.start;
                self.closed = true;
            }
        }
    }
}

struct Tokens<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Tokens<'a> {
    fn new(text: &'a str) -> Self {
        Self {
            bytes: text.as_bytes(),
            at: 0,
        }
    }

    /// Skips whitespace and commas; false at the end.
    fn skip_separators(&mut self) -> bool {
        while self.at < self.bytes.len()
            && (self.bytes[self.at].is_ascii_whitespace() || self.bytes[self.at] == b',')
        {
            self.at += 1;
        }
        self.at < self.bytes.len()
    }

    fn command(&mut self) -> Option<char> {
        let c = *self.bytes.get(self.at)? as char;
        if c.is_ascii_alphabetic() && c != 'e' && c != 'E' {
            self.at += 1;
            Some(c)
        } else {
            None
        }
    }

    fn number(&mut self) -> Result<f64, String> {
        let start = self.at;
        let b = self.bytes;
        let mut i = self.at;
        if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
            i += 1;
        }
        let mut dot = false;
        while i < b.len() && (b[i].is_ascii_digit() || (b[i] == b'.' && !dot)) {
            dot |= b[i] == b'.';
            i += 1;
        }
        if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
            let mut j = i + 1;
            if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
                j += 1;
            }
            if j < b.len() && b[j].is_ascii_digit() {
                i = j;
                while i < b.len() && b[i].is_ascii_digit() {
                    i += 1;
                }
            }
        }
        let text = std::str::from_utf8(&b[start..i]).unwrap_or("");
        self.at = i;
        text.parse::<f64>().map_err(|_| {
            let near: String = String::from_utf8_lossy(&b[start..b.len().min(start + 12)]).into();
            format!("expected a number, found {near:?}")
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_commands_and_compact_numbers() {
        let p = flatten("m1,1 h2 v2 l-2-0z", 4).unwrap();
        assert_eq!(
            p,
            vec![
                DVec2::new(1.0, 1.0),
                DVec2::new(3.0, 1.0),
                DVec2::new(3.0, 3.0),
                DVec2::new(1.0, 3.0),
                DVec2::new(1.0, 1.0)
            ]
        );
        assert_eq!(numbers("1-2.5.5e1").unwrap(), vec![1.0, -2.5, 5.0]);
    }

    #[test]
    fn arcs_and_garbage_are_errors() {
        assert!(flatten("M0 0 A 1 1 0 0 1 2 2 Z", 4).is_err());
        assert!(flatten("M0 0 L x y", 4).is_err());
        assert!(flatten("L 1 1", 4).is_err());
    }
}
