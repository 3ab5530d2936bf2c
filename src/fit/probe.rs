//! Dorsal rays through a voxelized figure (dissertation 8.1: "rays are cast dorsally").

use super::DorsalProbe;
use crate::voxel::Solid;
use glam::DVec3;

/// Ray marching step as a fraction of the voxel size: half a voxel never skips a voxel the ray
/// crosses by more than half its width.
const STEP: f64 = 0.5;

impl DorsalProbe for Solid {
    /// Marches from `origin` along `direction` in half-voxel steps and returns the distance to
    /// the first step that is outside the figure after having been inside; `None` when the ray
    /// never meets the inside or the direction is zero.
    fn depth(&self, origin: DVec3, direction: DVec3) -> Option<f64> {
        let direction = direction.try_normalize()?;
        let h = self.grid.voxel_size * STEP;
        let span = self.grid.voxel_size * self.grid.dims.iter().map(|&d| d as f64).sum::<f64>();
        let steps = (span / h).ceil() as usize;
        let mut was_inside = false;
        for k in 0..=steps {
            let p = origin + direction * (k as f64 * h);
            let inside = self
                .grid
                .voxel_at(p)
                .is_some_and(|c| self.inside[self.grid.index(c)]);
            if inside {
                was_inside = true;
            } else if was_inside {
                return Some(k as f64 * h);
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::voxel::{voxelize, VoxelOptions, VoxelSize};

    #[test]
    fn dorsal_depth_of_a_box() {
        let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::new(1.0, 2.0, 1.0));
        let options = VoxelOptions {
            size: VoxelSize::Fraction(1.0 / 40.0),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        let centre = DVec3::new(0.5, 1.0, 0.5);
        let up = solid.depth(centre, DVec3::Y).unwrap();
        assert!((up - 1.0).abs() < 0.06, "{up}");
        let side = solid.depth(centre, DVec3::new(3.0, 0.0, 0.0)).unwrap();
        assert!((side - 0.5).abs() < 0.06, "{side}");
        assert_eq!(solid.depth(DVec3::new(5.0, 5.0, 5.0), DVec3::X), None);
        assert_eq!(solid.depth(centre, DVec3::ZERO), None);
    }

    #[test]
    fn voxel_paths_carry_radii_in_mesh_units() {
        let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::new(1.0, 2.0, 1.0));
        let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
        let dist = crate::distance::edt(&solid);
        let deepest = dist.deepest();
        let (points, radii) = super::super::voxel_path(&dist, &[deepest]).unwrap();
        assert!((radii[0] - 0.5).abs() < 0.03, "{}", radii[0]);
        assert!((points[0] - DVec3::new(0.5, 1.0, 0.5)).length() < 1.0);
        assert!(super::super::voxel_path(&dist, &[usize::MAX]).is_err());
    }
}
