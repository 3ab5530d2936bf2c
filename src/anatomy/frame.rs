//! The figure's body frame: up, forward and left.

use super::AnatomyError;
use glam::DVec3;
use serde::Serialize;

/// Orthonormal body directions in the mesh frame. `left = up × forward`, so with +Y up and +Z
/// forward the figure's left is +X (the refdata convention).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Frame {
    /// Up (unit).
    pub up: DVec3,
    /// Forward (unit, perpendicular to up).
    pub forward: DVec3,
    /// The figure's left (unit).
    pub left: DVec3,
}

impl Frame {
    /// The frame from an up vector and an approximate forward vector (its component along up
    /// is removed, ch.7.3.2: forward need not be axis-aligned).
    ///
    /// # Errors
    /// [`AnatomyError::InvalidOrientation`] when either vector is zero or not finite, or when
    /// forward is (nearly) parallel to up.
    pub fn new(up: DVec3, forward: DVec3) -> Result<Self, AnatomyError> {
        let up = up
            .try_normalize()
            .ok_or_else(|| AnatomyError::InvalidOrientation {
                detail: format!("up {up} is zero or not finite"),
            })?;
        let f = forward
            .try_normalize()
            .ok_or_else(|| AnatomyError::InvalidOrientation {
                detail: format!("forward {forward} is zero or not finite"),
            })?;
        let forward = (f - up * f.dot(up))
            .try_normalize()
            .filter(|_| f.dot(up).abs() < 0.99)
            .ok_or_else(|| AnatomyError::InvalidOrientation {
                detail: format!("forward {forward} is parallel to up {up}"),
            })?;
        Ok(Self {
            up,
            forward,
            left: up.cross(forward),
        })
    }
}

/// Parses a direction: an axis `+X`, `-y`, `Z`... or a vector `x,y,z`.
///
/// # Errors
/// A message naming the text when it is neither.
pub fn parse_direction(text: &str) -> Result<DVec3, String> {
    let t = text.trim();
    let (sign, axis) = match t.as_bytes().first() {
        Some(b'-') => (-1.0, &t[1..]),
        Some(b'+') => (1.0, &t[1..]),
        _ => (1.0, t),
    };
    let v = match axis.to_ascii_lowercase().as_str() {
        "x" => Some(DVec3::X),
        "y" => Some(DVec3::Y),
        "z" => Some(DVec3::Z),
        _ => None,
    };
    if let Some(v) = v {
        return Ok(v * sign);
    }
    let parts: Vec<f64> = t
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| {
            format!("direction {text:?} is neither an axis (+Y, -Z...) nor a vector x,y,z")
        })?;
    match parts.as_slice() {
        [x, y, z]
            if DVec3::new(*x, *y, *z).length() > 0.0
                && x.is_finite()
                && y.is_finite()
                && z.is_finite() =>
        {
            Ok(DVec3::new(*x, *y, *z))
        }
        _ => Err(format!(
            "direction {text:?} is neither an axis (+Y, -Z...) nor a non-zero vector x,y,z"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_frame_has_left_at_plus_x_and_directions_parse() {
        let f = Frame::new(DVec3::Y, DVec3::Z).unwrap();
        assert_eq!(f.left, DVec3::X);
        assert_eq!(parse_direction("-z").unwrap(), DVec3::NEG_Z);
        assert_eq!(parse_direction("+Y").unwrap(), DVec3::Y);
        assert_eq!(parse_direction("1,0,1").unwrap(), DVec3::new(1.0, 0.0, 1.0));
        assert!(parse_direction("up").is_err());
        assert!(parse_direction("0,0,0").is_err());
        assert!(Frame::new(DVec3::Y, DVec3::Y).is_err());
        let slanted = Frame::new(DVec3::Y, DVec3::new(0.0, 1.0, 1.0)).unwrap();
        assert!((slanted.forward - DVec3::Z).length() < 1e-12);
    }
}
