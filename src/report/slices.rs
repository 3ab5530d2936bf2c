//! Pictures of distance-map slices, so a person can look at the voxel stages.

use crate::distance::DistanceMap;
use crate::voxel::Solid;

/// An 8-bit RGB raster image, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct RgbImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height * 3` bytes, row-major from the top-left pixel.
    pub pixels: Vec<u8>,
}

/// Colour of a distance `t` in `[0, 1]` on a perceptually ordered dark-blue → green → yellow ramp.
fn ramp(t: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 5] = [
        [68.0, 1.0, 84.0],
        [59.0, 82.0, 139.0],
        [33.0, 145.0, 140.0],
        [94.0, 201.0, 98.0],
        [253.0, 231.0, 37.0],
    ];
    let x = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let c = |k: usize| (STOPS[i][k] + f * (STOPS[i + 1][k] - STOPS[i][k])).round() as u8;
    [c(0), c(1), c(2)]
}

/// Renders the slice `index` perpendicular to `axis` (0 = x, 1 = y, 2 = z) of a distance map.
///
/// Interior voxels are coloured by distance (normalised by the map's maximum), exterior voxels
/// are near-black, and surface voxels from `solid` (if given) are light grey. The picture shows
/// the two remaining axes in right-handed order with the second one pointing up, each voxel as a
/// `scale` x `scale` pixel block. `index` is clamped to the grid.
pub fn distance_slice(
    map: &DistanceMap,
    solid: Option<&Solid>,
    axis: usize,
    index: usize,
    scale: u32,
) -> RgbImage {
    let axis = axis.min(2);
    let dims = map.grid.dims;
    // Horizontal and vertical axes of the picture: for a y-slice, x right and z up would be a
    // top view; we choose (x, z) for y, (z, y) for x and (x, y) for z (front view).
    let (h_axis, v_axis) = match axis {
        0 => (2, 1),
        1 => (0, 2),
        _ => (0, 1),
    };
    let index = index.min(dims[axis].saturating_sub(1));
    let scale = scale.max(1);
    let (w, h) = (dims[h_axis] as u32, dims[v_axis] as u32);
    let (width, height) = (w * scale, h * scale);
    let max = map.max_distance().max(1.0);
    let mut pixels = vec![0u8; (width * height * 3) as usize];
    for v in 0..h {
        for u in 0..w {
            let mut c = [0usize; 3];
            c[axis] = index;
            c[h_axis] = u as usize;
            c[v_axis] = v as usize;
            let i = map.grid.index(c);
            let colour = if map.squared[i] > 0 {
                ramp(map.distance(i) / max)
            } else if solid.is_some_and(|s| s.surface[i]) {
                [190, 190, 190]
            } else {
                [16, 16, 20]
            };
            let row0 = (h - 1 - v) * scale;
            for dy in 0..scale {
                for dx in 0..scale {
                    let p = (((row0 + dy) * width + u * scale + dx) * 3) as usize;
                    pixels[p..p + 3].copy_from_slice(&colour);
                }
            }
        }
    }
    RgbImage {
        width,
        height,
        pixels,
    }
}

/// Encodes an image as PNG bytes.
///
/// # Errors
/// Only if the encoder fails (e.g. an empty image).
pub fn png_bytes(image: &RgbImage) -> std::io::Result<Vec<u8>> {
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, image.width, image.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
        writer
            .write_image_data(&image.pixels)
            .map_err(std::io::Error::other)?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::voxel::{voxelize, VoxelOptions, VoxelSize};
    use glam::DVec3;

    #[test]
    fn slice_through_a_sphere_is_brightest_in_the_middle() {
        let mesh = Mesh::uv_sphere(DVec3::ZERO, 1.0, 16, 32);
        let options = VoxelOptions {
            size: VoxelSize::Fraction(1.0 / 20.0),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        let map = crate::distance::edt(&solid);
        let mid = solid.grid.dims[1] / 2;
        let image = distance_slice(&map, Some(&solid), 1, mid, 2);
        assert_eq!(image.pixels.len() as u32, image.width * image.height * 3);
        let at = |x: u32, y: u32| {
            let p = ((y * image.width + x) * 3) as usize;
            [image.pixels[p], image.pixels[p + 1], image.pixels[p + 2]]
        };
        assert_eq!(at(0, 0), [16, 16, 20]);
        let centre = at(image.width / 2, image.height / 2);
        assert!(centre[0] > 150 && centre[1] > 150, "centre {centre:?}");
        let png = png_bytes(&image).unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }
}
