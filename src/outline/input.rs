//! Reading a closed 2D outline: a CSV of points or an SVG path, flattened and validated.

use super::{OutlineError, OutlineOptions};
use glam::DVec2;
use std::path::Path;

/// A closed 2D outline: a simple polygon, counter-clockwise, without repeated points. The edge
/// from the last point back to the first is implied.
#[derive(Debug, Clone, PartialEq)]
pub struct Outline {
    /// The corners in counter-clockwise order, outline units, +Y up.
    pub points: Vec<DVec2>,
}

impl Outline {
    /// Validates `points` as a closed simple outline and orients it counter-clockwise. A last
    /// point equal to the first (an explicit closing point, as SVG's `Z` makes) is dropped and
    /// closes the outline; otherwise a last point within `options.closing_gap` mean edge
    /// lengths of the first counts as closed.
    ///
    /// # Errors
    /// [`OutlineError::NonFinite`], [`OutlineError::TooFewPoints`],
    /// [`OutlineError::DuplicatePoint`], [`OutlineError::OpenPath`],
    /// [`OutlineError::SelfIntersecting`], [`OutlineError::ZeroArea`].
    pub fn new(mut points: Vec<DVec2>, options: &OutlineOptions) -> Result<Self, OutlineError> {
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return Err(OutlineError::NonFinite { index });
        }
        let explicitly_closed = points.len() > 1 && points.first() == points.last();
        if explicitly_closed {
            points.pop();
        }
        if points.len() < 3 {
            return Err(OutlineError::TooFewPoints {
                count: points.len(),
            });
        }
        check_duplicates(&points)?;
        if !explicitly_closed {
            check_closed(&points, options.closing_gap)?;
        }
        if let Some((first, second, at)) = super::simple::first_crossing(&points) {
            return Err(OutlineError::SelfIntersecting {
                first,
                second,
                x: at.x,
                y: at.y,
            });
        }
        let area = signed_area(&points);
        if area.is_nan() || area == 0.0 {
            return Err(OutlineError::ZeroArea);
        }
        if area < 0.0 {
            points.reverse();
        }
        Ok(Self { points })
    }

    /// Perimeter, outline units.
    pub fn perimeter(&self) -> f64 {
        perimeter(&self.points)
    }

    /// Signed area (positive: counter-clockwise), outline units squared.
    pub fn area(&self) -> f64 {
        signed_area(&self.points)
    }

    /// Minimum and maximum corners of the bounding box.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        bounds(&self.points)
    }

    /// Whether `p` lies inside the outline (even-odd rule; points on the boundary may go
    /// either way).
    pub fn contains(&self, p: DVec2) -> bool {
        contains(&self.points, p)
    }
}

/// Perimeter of the closed polygon `points`.
pub(crate) fn perimeter(points: &[DVec2]) -> f64 {
    (0..points.len())
        .map(|i| points[i].distance(points[(i + 1) % points.len()]))
        .sum()
}

/// Signed area of the closed polygon `points` (shoelace formula).
pub(crate) fn signed_area(points: &[DVec2]) -> f64 {
    0.5 * (0..points.len())
        .map(|i| points[i].perp_dot(points[(i + 1) % points.len()]))
        .sum::<f64>()
}

/// Bounding box of `points` (`(+inf, -inf)` when empty).
pub(crate) fn bounds(points: &[DVec2]) -> (DVec2, DVec2) {
    points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

/// Even-odd point in polygon test.
pub(crate) fn contains(points: &[DVec2], p: DVec2) -> bool {
    let mut inside = false;
    let n = points.len();
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (points[i], points[j]);
        if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
            inside = !inside;
        }
        j = i;
    }
    inside
}

fn check_duplicates(points: &[DVec2]) -> Result<(), OutlineError> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        points[a]
            .x
            .total_cmp(&points[b].x)
            .then(points[a].y.total_cmp(&points[b].y))
            .then(a.cmp(&b))
    });
    for w in order.windows(2) {
        if points[w[0]] == points[w[1]] {
            let (first, second) = (w[0].min(w[1]), w[0].max(w[1]));
            return Err(OutlineError::DuplicatePoint {
                first,
                second,
                x: points[first].x,
                y: points[first].y,
            });
        }
    }
    Ok(())
}

fn check_closed(points: &[DVec2], closing_gap: f64) -> Result<(), OutlineError> {
    let n = points.len();
    let open_length: f64 = (0..n - 1).map(|i| points[i].distance(points[i + 1])).sum();
    let mean = open_length / (n - 1) as f64;
    let gap = points[n - 1].distance(points[0]);
    let allowed = closing_gap * mean;
    if gap > allowed {
        return Err(OutlineError::OpenPath { gap, allowed });
    }
    Ok(())
}

/// Reads an outline from a `.csv` ([`parse_csv`]) or `.svg` ([`parse_svg`]) file and validates
/// it ([`Outline::new`]).
///
/// # Errors
/// [`OutlineError::Io`], [`OutlineError::UnknownFormat`], and the errors of the parsers and of
/// [`Outline::new`].
pub fn read_outline(path: &Path, options: &OutlineOptions) -> Result<Outline, OutlineError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    let text = std::fs::read_to_string(path).map_err(|cause| OutlineError::Io {
        path: path.to_path_buf(),
        cause,
    })?;
    let points = match extension.as_str() {
        "csv" | "txt" => parse_csv(&text)?,
        "svg" => parse_svg(&text, options)?,
        _ => return Err(OutlineError::UnknownFormat { extension }),
    };
    Outline::new(points, options)
}

/// Parses `x,y` rows (separated by commas, semicolons, tabs or spaces). Empty lines, lines
/// starting with `#`, and a first line that is not numeric (a header) are skipped.
///
/// # Errors
/// [`OutlineError::Parse`] naming the line.
pub fn parse_csv(text: &str) -> Result<Vec<DVec2>, OutlineError> {
    let mut points = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let numbers: Result<Vec<f64>, _> = fields.iter().map(|f| f.parse::<f64>()).collect();
        match numbers {
            Ok(v) if v.len() >= 2 => points.push(DVec2::new(v[0], v[1])),
            Err(_) if points.is_empty() && k == first_content_line(text) => continue,
            _ => {
                return Err(OutlineError::Parse {
                    location: format!("line {}", k + 1),
                    message: format!("expected two numbers x,y, found {line:?}"),
                })
            }
        }
    }
    Ok(points)
}

fn first_content_line(text: &str) -> usize {
    text.lines()
        .position(|l| {
            let l = l.trim();
            !l.is_empty() && !l.starts_with('#')
        })
        .unwrap_or(0)
}

/// Parses the first `<path d="...">` (or `<polygon points="...">`) of an SVG document into
/// points: moveto, lineto (`M L H V`), cubic and quadratic Béziers (`C S Q T`, each flattened
/// into `options.curve_segments` lines) and closepath (`Z`), absolute and relative. SVG's y
/// axis points down; it is flipped so the outline is upright in +Y up. Transforms are ignored.
///
/// # Errors
/// [`OutlineError::Parse`] when there is no path, for arcs (`A`: convert them to curves), a
/// second subpath, or malformed numbers.
pub fn parse_svg(text: &str, options: &OutlineOptions) -> Result<Vec<DVec2>, OutlineError> {
    let points = if let Some(d) = attribute(text, "path", "d") {
        super::svg_path::flatten(&d, options.curve_segments)?
    } else if let Some(list) = attribute(text, "polygon", "points") {
        let numbers = super::svg_path::numbers(&list).map_err(|message| OutlineError::Parse {
            location: "polygon points".into(),
            message,
        })?;
        numbers
            .chunks_exact(2)
            .map(|c| DVec2::new(c[0], c[1]))
            .collect()
    } else {
        return Err(OutlineError::Parse {
            location: "the SVG document".into(),
            message: "no <path d=...> or <polygon points=...> element: draw the outline as a path"
                .into(),
        });
    };
    Ok(points.into_iter().map(|p| DVec2::new(p.x, -p.y)).collect())
}

/// The value of attribute `name` of the first `<element ...>` in `text`.
fn attribute(text: &str, element: &str, name: &str) -> Option<String> {
    let open = format!("<{element}");
    let mut rest = text;
    while let Some(start) = rest.find(&open) {
        let after = &rest[start + open.len()..];
        if !after.starts_with(|c: char| c.is_whitespace()) {
            rest = after;
            continue;
        }
        let end = after.find('>')?;
        let tag = &after[..end];
        let mut search = tag;
        while let Some(pos) = search.find(name) {
            let before_ok = pos == 0 || search[..pos].ends_with(|c: char| c.is_whitespace());
            let tail = search[pos + name.len()..].trim_start();
            if before_ok {
                if let Some(tail) = tail.strip_prefix('=') {
                    let tail = tail.trim_start();
                    let quote = tail.chars().next()?;
                    if quote == '"' || quote == '\'' {
                        let value = &tail[1..];
                        let close = value.find(quote)?;
                        return Some(value[..close].to_string());
                    }
                }
            }
            search = &search[pos + name.len()..];
        }
        return None;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> OutlineOptions {
        OutlineOptions::default()
    }

    #[test]
    fn csv_with_header_and_closing_point_reads_a_ccw_square() {
        let text = "x,y\n0,0\n0,1\n1,1\n1,0\n0,0\n";
        let outline = Outline::new(parse_csv(text).unwrap(), &opts()).unwrap();
        assert_eq!(outline.points.len(), 4);
        assert!(outline.area() > 0.99);
    }

    #[test]
    fn csv_garbage_names_the_line() {
        let err = parse_csv("0,0\n1,zz\n").unwrap_err();
        assert!(err.to_string().contains("line 2"), "{err}");
    }

    #[test]
    fn svg_path_with_curves_is_flattened_and_flipped() {
        let svg = r#"<svg><path fill="none" d="M 0 0 L 10 0 C 12 0 12 10 10 10 L 0 10 Z"/></svg>"#;
        let points = parse_svg(svg, &opts()).unwrap();
        assert!(points.len() > 4);
        assert!(points.iter().all(|p| p.y <= 0.0));
        let outline = Outline::new(points, &opts()).unwrap();
        assert!(outline.area() > 100.0);
    }

    #[test]
    fn bad_outlines_give_named_errors() {
        let o = opts();
        let two = vec![DVec2::ZERO, DVec2::X];
        assert!(matches!(
            Outline::new(two, &o),
            Err(OutlineError::TooFewPoints { count: 2 })
        ));
        let dup = vec![DVec2::ZERO, DVec2::X, DVec2::X, DVec2::ONE, DVec2::Y];
        assert!(matches!(
            Outline::new(dup, &o),
            Err(OutlineError::DuplicatePoint {
                first: 1,
                second: 2,
                ..
            })
        ));
        let bow = vec![DVec2::ZERO, DVec2::ONE, DVec2::X, DVec2::Y];
        assert!(matches!(
            Outline::new(bow, &o),
            Err(OutlineError::SelfIntersecting { .. })
        ));
        let open: Vec<DVec2> = (0..20)
            .map(|i| DVec2::new(i as f64, (i as f64).sin()))
            .collect();
        assert!(matches!(
            Outline::new(open, &o),
            Err(OutlineError::OpenPath { .. })
        ));
        let nan = vec![DVec2::ZERO, DVec2::new(f64::NAN, 0.0), DVec2::ONE];
        assert!(matches!(
            Outline::new(nan, &o),
            Err(OutlineError::NonFinite { index: 1 })
        ));
    }
}
