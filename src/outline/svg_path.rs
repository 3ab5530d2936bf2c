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
    let segments = segments.max(1);
    let mut tokens = Tokens::new(d);
    let mut points: Vec<DVec2> = Vec::new();
    let mut current = DVec2::ZERO;
    let mut start = DVec2::ZERO;
    let mut last_control: Option<(char, DVec2)> = None;
    let mut command: Option<char> = None;
    let mut index = 0usize;
    let mut closed = false;
    while tokens.skip_separators() {
        if closed {
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
        if points.is_empty() && !c.eq_ignore_ascii_case(&'M') {
            return Err(err(index, "path data must start with a moveto 'M'".into()));
        }
        command = Some(c);
        let relative = c.is_ascii_lowercase();
        let base = if relative { current } else { DVec2::ZERO };
        let mut read = |n: usize| -> Result<Vec<f64>, OutlineError> {
            (0..n)
                .map(|_| {
                    tokens.skip_separators();
                    tokens.number().map_err(|m| err(index, m))
                })
                .collect()
        };
        match c.to_ascii_uppercase() {
            'M' => {
                if !points.is_empty() {
                    return Err(err(
                        index,
                        "a second subpath: give one closed outline per file".into(),
                    ));
                }
                let v = read(2)?;
                current = base + DVec2::new(v[0], v[1]);
                start = current;
                points.push(current);
                last_control = None;
            }
            'L' => {
                let v = read(2)?;
                current = base + DVec2::new(v[0], v[1]);
                points.push(current);
                last_control = None;
            }
            'H' => {
                let v = read(1)?;
                current.x = if relative { current.x + v[0] } else { v[0] };
                points.push(current);
                last_control = None;
            }
            'V' => {
                let v = read(1)?;
                current.y = if relative { current.y + v[0] } else { v[0] };
                points.push(current);
                last_control = None;
            }
            'C' | 'S' => {
                let (c1, c2, end) = if c.eq_ignore_ascii_case(&'C') {
                    let v = read(6)?;
                    (
                        base + DVec2::new(v[0], v[1]),
                        base + DVec2::new(v[2], v[3]),
                        base + DVec2::new(v[4], v[5]),
                    )
                } else {
                    let v = read(4)?;
                    let c1 = match last_control {
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
                for k in 1..=segments {
                    let t = k as f64 / segments as f64;
                    let u = 1.0 - t;
                    points.push(
                        u * u * u * p0
                            + 3.0 * u * u * t * c1
                            + 3.0 * u * t * t * c2
                            + t * t * t * end,
                    );
                }
                current = end;
                last_control = Some(('C', c2));
            }
            'Q' | 'T' => {
                let (c1, end) = if c.eq_ignore_ascii_case(&'Q') {
                    let v = read(4)?;
                    (base + DVec2::new(v[0], v[1]), base + DVec2::new(v[2], v[3]))
                } else {
                    let v = read(2)?;
                    let c1 = match last_control {
                        Some(('Q', p)) => 2.0 * current - p,
                        _ => current,
                    };
                    (c1, base + DVec2::new(v[0], v[1]))
                };
                let p0 = current;
                for k in 1..=segments {
                    let t = k as f64 / segments as f64;
                    let u = 1.0 - t;
                    points.push(u * u * p0 + 2.0 * u * t * c1 + t * t * end);
                }
                current = end;
                last_control = Some(('Q', c1));
            }
            'Z' => {
                if points.last() != Some(&start) {
                    points.push(start);
                }
                current = start;
                closed = true;
                command = None;
            }
            'A' => {
                return Err(err(
                    index,
                    "elliptical arcs ('A') are not supported: convert arcs to curves".into(),
                ))
            }
            other => return Err(err(index, format!("unknown path command '{other}'"))),
        }
    }
    if points.is_empty() {
        return Err(err(0, "the path is empty".into()));
    }
    Ok(points)
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
