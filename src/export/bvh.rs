//! Biovision hierarchy (`.bvh`): the skeleton's rest pose with one motion frame.

use super::{check_skeleton, io_error, ExportError};
use crate::skeleton::{JointId, Skeleton};
use glam::DVec3;
use std::fmt::Write as _;
use std::path::Path;

/// Options of [`bvh_text`] and [`write_bvh`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BvhOptions {
    /// Seconds per frame written as `Frame Time`. Default 1/30 (30 frames per second, the
    /// common motion-capture rate).
    pub frame_time: f64,
    /// Length of the `End Site` offset of a leaf joint, as a fraction of the bone leading to it,
    /// continued along that bone. Default 0.25: short enough not to overshoot the figure,
    /// long enough for viewers that draw bones from joint to end site.
    pub end_site_fraction: f64,
    /// Digits after the decimal point of offsets and channel values. Default 6 (micrometres
    /// for a figure in metres).
    pub decimals: usize,
}

impl Default for BvhOptions {
    fn default() -> Self {
        Self {
            frame_time: 1.0 / 30.0,
            end_site_fraction: 0.25,
            decimals: 6,
        }
    }
}

/// One step of the depth-first walk over the hierarchy.
enum Step {
    Open(JointId),
    Close,
}

/// The skeleton as BVH text.
///
/// `HIERARCHY`: every root joint becomes a `ROOT` with six channels (`Xposition Yposition
/// Zposition Zrotation Xrotation Yrotation`), every other joint a `JOINT` with three rotation
/// channels, children in joint order; `OFFSET`s are positions relative to the parent in the
/// skeleton's units and axes (a root's offset is its position). A non-deforming leaf named
/// `<parent>_end` (what BVH readers, including [`crate::eval::parse_bvh`], make of an end
/// site) is written back as its parent's `End Site`; every other leaf gets an `End Site`
/// [`BvhOptions::end_site_fraction`] of its bone beyond it. BVH has no rest orientations:
/// joint frames and DOF limits are not written, and the rest pose is all channels zero.
/// `MOTION`: one frame, the rest pose (root position channels hold the root's position, the
/// convention of Blender's exporter; rotations zero).
///
/// # Errors
/// [`ExportError::EmptySkeleton`], [`ExportError::InvalidSkeleton`], and
/// [`ExportError::InvalidName`] for an empty name, one with line breaks, braces or leading or
/// trailing whitespace.
pub fn bvh_text(skeleton: &Skeleton, options: &BvhOptions) -> Result<String, ExportError> {
    check_skeleton(skeleton)?;
    for joint in &skeleton.joints {
        check_name(&joint.name)?;
    }
    let n = skeleton.len();
    let mut children: Vec<Vec<JointId>> = vec![Vec::new(); n];
    for (k, joint) in skeleton.joints.iter().enumerate() {
        if let Some(p) = joint.parent {
            children[p.0].push(JointId(k));
        }
    }
    // A joint's end site: the `<name>_end` leaf it owns, if any.
    let mut end_site: Vec<Option<JointId>> = vec![None; n];
    for (k, joint) in skeleton.joints.iter().enumerate() {
        if let Some(p) = joint.parent {
            let is_end = !joint.deform
                && children[k].is_empty()
                && joint.name == format!("{}_end", skeleton.joint(p).name);
            if is_end && end_site[p.0].is_none() {
                end_site[p.0] = Some(JointId(k));
            }
        }
    }
    let written = |k: JointId| !end_site.contains(&Some(k));
    let number = |v: f64| format_number(v, options.decimals);
    let triple = |v: DVec3| format!("{} {} {}", number(v.x), number(v.y), number(v.z));

    let mut out = String::from("HIERARCHY\n");
    let mut motion: Vec<String> = Vec::new();
    let mut stack: Vec<Step> = (0..n)
        .rev()
        .filter(|&k| skeleton.joints[k].parent.is_none())
        .map(|k| Step::Open(JointId(k)))
        .collect();
    let mut depth = 0usize;
    while let Some(step) = stack.pop() {
        match step {
            Step::Close => {
                depth -= 1;
                let _ = writeln!(out, "{}}}", "\t".repeat(depth));
            }
            Step::Open(id) => {
                let joint = skeleton.joint(id);
                let indent = "\t".repeat(depth);
                let (keyword, offset) = match joint.parent {
                    None => ("ROOT", joint.position),
                    Some(p) => ("JOINT", joint.position - skeleton.joint(p).position),
                };
                let _ = writeln!(out, "{indent}{keyword} {}", joint.name);
                let _ = writeln!(out, "{indent}{{");
                let _ = writeln!(out, "{indent}\tOFFSET {}", triple(offset));
                if joint.parent.is_none() {
                    let _ = writeln!(
                        out,
                        "{indent}\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"
                    );
                    motion.push(format!("{} 0 0 0", triple(joint.position)));
                } else {
                    let _ = writeln!(out, "{indent}\tCHANNELS 3 Zrotation Xrotation Yrotation");
                    motion.push("0 0 0".into());
                }
                let joint_children: Vec<JointId> = children[id.0]
                    .iter()
                    .copied()
                    .filter(|&c| written(c))
                    .collect();
                let end = match end_site[id.0] {
                    Some(e) => Some(skeleton.joint(e).position - joint.position),
                    None if joint_children.is_empty() => Some(match joint.parent {
                        Some(p) => {
                            (joint.position - skeleton.joint(p).position)
                                * options.end_site_fraction
                        }
                        None => DVec3::ZERO,
                    }),
                    None => None,
                };
                if let Some(end) = end {
                    let _ = writeln!(out, "{indent}\tEnd Site");
                    let _ = writeln!(out, "{indent}\t{{");
                    let _ = writeln!(out, "{indent}\t\tOFFSET {}", triple(end));
                    let _ = writeln!(out, "{indent}\t}}");
                }
                depth += 1;
                stack.push(Step::Close);
                stack.extend(joint_children.iter().rev().map(|&c| Step::Open(c)));
            }
        }
    }
    let _ = writeln!(out, "MOTION");
    let _ = writeln!(out, "Frames: 1");
    let _ = writeln!(out, "Frame Time: {}", number(options.frame_time));
    let _ = writeln!(out, "{}", motion.join(" "));
    Ok(out)
}

/// Writes [`bvh_text`] to `path` atomically.
///
/// # Errors
/// As [`bvh_text`], and [`ExportError::Io`] when the file cannot be written.
pub fn write_bvh(
    path: &Path,
    skeleton: &Skeleton,
    options: &BvhOptions,
) -> Result<(), ExportError> {
    let text = bvh_text(skeleton, options)?;
    crate::output::write_atomic(path, text.as_bytes()).map_err(|cause| io_error(path, cause))
}

/// Fixed-point text of `v` with `decimals` digits, without a negative zero.
fn format_number(v: f64, decimals: usize) -> String {
    let text = format!("{v:.decimals$}");
    if text.starts_with('-') && text[1..].chars().all(|c| c == '0' || c == '.') {
        text[1..].to_owned()
    } else {
        text
    }
}

/// Rejects names a BVH reader would split or misread.
fn check_name(name: &str) -> Result<(), ExportError> {
    let reason = if name.is_empty() {
        Some("it is empty")
    } else if name.contains(['\n', '\r']) {
        Some("it contains a line break")
    } else if name.contains(['{', '}']) {
        Some("it contains a brace")
    } else if name.trim() != name {
        Some("it starts or ends with whitespace")
    } else {
        None
    };
    match reason {
        Some(reason) => Err(ExportError::InvalidName {
            name: name.to_owned(),
            format: "BVH",
            reason,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_fixed_digits_and_no_negative_zero() {
        assert_eq!(format_number(-0.0000001, 6), "0.000000");
        assert_eq!(format_number(-1.5, 3), "-1.500");
        assert_eq!(format_number(2.0, 2), "2.00");
    }

    #[test]
    fn names_that_break_bvh_are_rejected() {
        assert!(check_name("upper arm").is_ok());
        assert!(check_name("").is_err());
        assert!(check_name("a\nb").is_err());
        assert!(check_name("a{").is_err());
        assert!(check_name(" a").is_err());
    }
}
