//! Biovision hierarchy (BVH) reader: the rest pose from the HIERARCHY section.

use super::reference::model_name;
use super::{EvalError, ReferenceRig, RigFormat};
use crate::skeleton::{Joint, JointId, Skeleton};
use glam::DVec3;
use std::collections::BTreeMap;
use std::path::Path;

/// Deepest joint nesting accepted; deeper files are rejected instead of overflowing the stack.
const MAX_DEPTH: usize = 512;

/// Parses the HIERARCHY section of a BVH file into a rest-pose skeleton.
///
/// Each `ROOT`/`JOINT` becomes a deforming joint at the sum of the `OFFSET`s along its chain
/// (file units, usually centimetres; BVH declares none). An `End Site` becomes a non-deforming
/// joint named `<parent>_end`. `CHANNELS` and the `MOTION` section are ignored. `origin` names
/// the source in messages and gives the model name.
///
/// # Errors
/// [`EvalError::Parse`] with the line number for a malformed hierarchy,
/// [`EvalError::InvalidSkeleton`] for duplicate joint names.
pub fn parse_bvh(text: &str, origin: &Path) -> Result<ReferenceRig, EvalError> {
    let mut parser = Parser {
        tokens: tokenize(text),
        next: 0,
        joints: Vec::new(),
        origin,
    };
    parser.expect("HIERARCHY")?;
    loop {
        match parser.peek() {
            Some((_, "ROOT")) => {
                parser.next += 1;
                let name = parser.name()?;
                parser.joint(name, None, DVec3::ZERO, 0)?;
            }
            None | Some((_, "MOTION")) => break,
            Some((line, other)) => {
                return Err(parser.error(line, format!("expected ROOT or MOTION, found {other:?}")))
            }
        }
    }
    if parser.joints.is_empty() {
        return Err(parser.error(0, "the HIERARCHY has no ROOT joint".into()));
    }
    let mut seen = std::collections::HashSet::new();
    if let Some(dup) = parser.joints.iter().find(|j| !seen.insert(j.name.as_str())) {
        return Err(EvalError::InvalidSkeleton {
            path: origin.to_owned(),
            message: format!(
                "joint name {:?} occurs twice; names must be unique",
                dup.name
            ),
        });
    }
    Ok(ReferenceRig {
        skeleton: Skeleton {
            joints: parser.joints,
        },
        canonical: BTreeMap::new(),
        model: model_name(origin),
        rig: Some("bvh".into()),
        units: None,
        format: RigFormat::Bvh,
    })
}

/// Whitespace-separated tokens with their 1-based line numbers. A `ROOT`/`JOINT` line keeps its
/// whole remainder as one name token (names may contain spaces); a trailing `{` is split off.
fn tokenize(text: &str) -> Vec<(usize, String)> {
    let mut tokens = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line_no = index + 1;
        let trimmed = line.trim();
        let mut words = trimmed.split_whitespace();
        match words.next() {
            Some(keyword @ ("ROOT" | "JOINT")) => {
                tokens.push((line_no, keyword.to_owned()));
                let rest = trimmed[keyword.len()..].trim();
                let (name, brace) = match rest.strip_suffix('{') {
                    Some(name) => (name.trim(), true),
                    None => (rest, false),
                };
                if !name.is_empty() {
                    tokens.push((line_no, name.to_owned()));
                }
                if brace {
                    tokens.push((line_no, "{".to_owned()));
                }
            }
            Some(first) => {
                tokens.push((line_no, first.to_owned()));
                tokens.extend(words.map(|w| (line_no, w.to_owned())));
            }
            None => {}
        }
    }
    tokens
}

struct Parser<'a> {
    tokens: Vec<(usize, String)>,
    next: usize,
    joints: Vec<Joint>,
    origin: &'a Path,
}

impl Parser<'_> {
    fn peek(&self) -> Option<(usize, &str)> {
        self.tokens.get(self.next).map(|(l, t)| (*l, t.as_str()))
    }

    fn line(&self) -> usize {
        self.tokens
            .get(self.next)
            .or(self.tokens.last())
            .map_or(0, |(l, _)| *l)
    }

    fn error(&self, line: usize, message: String) -> EvalError {
        EvalError::Parse {
            path: self.origin.to_owned(),
            format: "bvh",
            message: if line > 0 {
                format!("line {line}: {message}")
            } else {
                message
            },
        }
    }

    fn take(&mut self) -> Result<(usize, String), EvalError> {
        let token = self
            .tokens
            .get(self.next)
            .cloned()
            .ok_or_else(|| self.error(self.line(), "unexpected end of file".into()))?;
        self.next += 1;
        Ok(token)
    }

    fn expect(&mut self, word: &str) -> Result<(), EvalError> {
        let (line, token) = self.take()?;
        if token == word {
            Ok(())
        } else {
            Err(self.error(line, format!("expected {word:?}, found {token:?}")))
        }
    }

    fn name(&mut self) -> Result<String, EvalError> {
        let (line, token) = self.take()?;
        if token == "{" {
            return Err(self.error(line, "a joint needs a name".into()));
        }
        Ok(token)
    }

    fn number(&mut self) -> Result<f64, EvalError> {
        let (line, token) = self.take()?;
        match token.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(value),
            _ => Err(self.error(line, format!("expected a number, found {token:?}"))),
        }
    }

    fn offset(&mut self) -> Result<DVec3, EvalError> {
        self.expect("OFFSET")?;
        Ok(DVec3::new(self.number()?, self.number()?, self.number()?))
    }

    /// Parses `{ OFFSET .. CHANNELS .. (JOINT|End Site)* }` after a joint name.
    fn joint(
        &mut self,
        name: String,
        parent: Option<JointId>,
        base: DVec3,
        depth: usize,
    ) -> Result<(), EvalError> {
        if depth > MAX_DEPTH {
            return Err(self.error(
                self.line(),
                format!("joints nested deeper than {MAX_DEPTH} levels"),
            ));
        }
        self.expect("{")?;
        let position = base + self.offset()?;
        let id = JointId(self.joints.len());
        self.joints.push(Joint {
            name,
            parent,
            position,
            deform: true,
            ..Default::default()
        });
        loop {
            let (line, token) = self.take()?;
            match token.as_str() {
                "CHANNELS" => {
                    let (count_line, count) = self.take()?;
                    let count: usize = count.parse().map_err(|_| {
                        self.error(
                            count_line,
                            format!("expected a channel count, found {count:?}"),
                        )
                    })?;
                    for _ in 0..count {
                        self.take()?;
                    }
                }
                "JOINT" => {
                    let child = self.name()?;
                    self.joint(child, Some(id), position, depth + 1)?;
                }
                "End" => {
                    self.expect("Site")?;
                    self.expect("{")?;
                    let end = position + self.offset()?;
                    self.expect("}")?;
                    let parent_name = &self.joints[id.0].name;
                    self.joints.push(Joint {
                        name: format!("{parent_name}_end"),
                        parent: Some(id),
                        position: end,
                        deform: false,
                        ..Default::default()
                    });
                }
                "}" => return Ok(()),
                other => {
                    return Err(self.error(
                        line,
                        format!("expected CHANNELS, JOINT, End Site or '}}', found {other:?}"),
                    ))
                }
            }
        }
    }
}
