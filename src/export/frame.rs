//! The output frame: glTF's +Y up, +Z forward, metres, reached from the mesh's own frame.

use crate::mesh::Mesh;
use crate::skeleton::Skeleton;
use glam::{DAffine3, DMat3, DQuat, DVec3};

/// A rotation and a uniform scale taking the frame the rig was fitted in (the input mesh's)
/// to the frame of the written file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputFrame {
    /// Turns the input's axes onto the file's.
    pub rotation: DQuat,
    /// Input units → file units (0.001 for millimetres → metres).
    pub scale: f64,
}

impl Default for OutputFrame {
    /// The input's own frame and units.
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl OutputFrame {
    /// The input's own frame and units (`--keep-frame`).
    pub const IDENTITY: Self = Self {
        rotation: DQuat::IDENTITY,
        scale: 1.0,
    };

    /// The frame that turns `up` onto +Y and `forward` onto +Z (glTF's convention: the
    /// figure's left, `up × forward`, onto +X) and multiplies lengths by `scale`.
    ///
    /// `up` and `forward` need not be unit; `forward`'s component along `up` is ignored. A
    /// `forward` parallel to `up` (or a zero vector) keeps the rotation that only turns up.
    ///
    /// # Example
    /// ```
    /// use glam::DVec3;
    /// use skelfit::export::OutputFrame;
    /// // Blender's Z-up, -Y forward → glTF's Y-up, +Z forward, millimetres → metres.
    /// let frame = OutputFrame::new(DVec3::Z, -DVec3::Y, 0.001);
    /// let head = frame.point(DVec3::new(0.0, 0.0, 1800.0));
    /// assert!((head - DVec3::new(0.0, 1.8, 0.0)).length() < 1e-12);
    /// ```
    pub fn new(up: DVec3, forward: DVec3, scale: f64) -> Self {
        let up = up.try_normalize().unwrap_or(DVec3::Y);
        let along = forward - up * forward.dot(up);
        let rotation = match along.try_normalize() {
            Some(forward) => {
                let left = up.cross(forward);
                // Rows are the input's left, up and forward: they map onto x, y, z.
                let to_file = DMat3::from_cols(left, up, forward).transpose();
                DQuat::from_mat3(&to_file).normalize()
            }
            None => DQuat::from_rotation_arc(up, DVec3::Y),
        };
        Self { rotation, scale }
    }

    /// Whether this frame changes nothing.
    pub fn is_identity(&self) -> bool {
        self.scale == 1.0 && self.rotation == DQuat::IDENTITY
    }

    /// The transform as an affine map (input → file).
    pub fn affine(&self) -> DAffine3 {
        DAffine3::from_scale_rotation_translation(
            DVec3::splat(self.scale),
            self.rotation,
            DVec3::ZERO,
        )
    }

    /// A point of the input in the file's frame.
    pub fn point(&self, p: DVec3) -> DVec3 {
        self.rotation * p * self.scale
    }

    /// The mesh in the file's frame (positions turned and scaled; triangles unchanged).
    pub fn mesh(&self, mesh: &Mesh) -> Mesh {
        mesh.transformed(|p| self.point(p))
    }

    /// The skeleton in the file's frame: rest positions turned and scaled, joint frames
    /// turned, so every bone keeps its length in file units and its roll.
    pub fn skeleton(&self, skeleton: &Skeleton) -> Skeleton {
        let mut out = skeleton.clone();
        for joint in &mut out.joints {
            joint.position = self.point(joint.position);
            joint.frame = (self.rotation * joint.frame).normalize();
        }
        out
    }
}

/// A length unit of the input mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    /// Millimetres.
    Millimetres,
    /// Centimetres.
    Centimetres,
    /// Metres.
    Metres,
    /// Inches.
    Inches,
}

/// What [`Units::guess`] decided, and how sure it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitsGuess {
    /// The units chosen.
    pub units: Units,
    /// Whether the height fell in one of the ranges of [`Units::guess`]; `false` means
    /// metres by default for a height outside all of them.
    pub confident: bool,
}

impl Units {
    /// Heights a figure standing 0.3-3 m tall has in each unit the guess considers, as
    /// `(units, lowest, highest)`. Inches overlap centimetres (a 1.8 m figure is 71 in or
    /// 180 cm), so they are never guessed.
    pub const GUESS_RANGES: [(Units, f64, f64); 3] = [
        (Units::Metres, 0.3, 3.0),
        (Units::Centimetres, 30.0, 300.0),
        (Units::Millimetres, 300.0, 3000.0),
    ];

    /// Metres per unit.
    pub fn metres(self) -> f64 {
        match self {
            Units::Millimetres => 0.001,
            Units::Centimetres => 0.01,
            Units::Metres => 1.0,
            Units::Inches => 0.0254,
        }
    }

    /// The unit's short name (`mm`, `cm`, `m`, `in`).
    pub fn symbol(self) -> &'static str {
        match self {
            Units::Millimetres => "mm",
            Units::Centimetres => "cm",
            Units::Metres => "m",
            Units::Inches => "in",
        }
    }

    /// The units of a figure `height` units tall (its extent along up): the first of
    /// [`Units::GUESS_RANGES`] holding it (human and animal figures measure 0.3-3 m), else
    /// metres, not confident.
    ///
    /// # Example
    /// ```
    /// use skelfit::export::Units;
    /// assert_eq!(Units::guess(1.7).units, Units::Metres);
    /// assert_eq!(Units::guess(172.0).units, Units::Centimetres);
    /// assert_eq!(Units::guess(1800.0).units, Units::Millimetres);
    /// assert!(!Units::guess(12.0).confident);
    /// ```
    pub fn guess(height: f64) -> UnitsGuess {
        Self::GUESS_RANGES
            .iter()
            .find(|(_, low, high)| (*low..=*high).contains(&height))
            .map_or(
                UnitsGuess {
                    units: Units::Metres,
                    confident: false,
                },
                |&(units, _, _)| UnitsGuess {
                    units,
                    confident: true,
                },
            )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_guesses_follow_the_ranges() {
        assert_eq!(Units::guess(0.3).units, Units::Metres);
        assert_eq!(Units::guess(250.0).units, Units::Centimetres);
        assert_eq!(Units::guess(2999.0).units, Units::Millimetres);
        assert!(!Units::guess(5000.0).confident);
        assert_eq!(Units::Inches.metres(), 0.0254);
    }

    #[test]
    fn axes_go_where_gltf_wants_them() {
        let frame = OutputFrame::new(DVec3::Z, -DVec3::Y, 1.0);
        assert!((frame.point(DVec3::Z) - DVec3::Y).length() < 1e-12);
        assert!((frame.point(-DVec3::Y) - DVec3::Z).length() < 1e-12);
        // Left = up × forward = Z × -Y = +X.
        assert!((frame.point(DVec3::X) - DVec3::X).length() < 1e-12);
        let same = OutputFrame::new(DVec3::Y, DVec3::Z, 1.0);
        assert!(same.rotation.angle_between(DQuat::IDENTITY) < 1e-12);
    }
}
