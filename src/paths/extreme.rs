//! Extreme points of the DMS seen from the heart (dissertation ch.5.2.4).

use super::{DmsGraph, PathOptions};
use crate::medial::MedialSurface;
use serde::Serialize;

/// A potential end effector: a DMS voxel whose depth from the heart is a maximum within a
/// neighbourhood.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ExtremePoint {
    /// DMS position (index into [`MedialSurface::voxels`]).
    pub position: usize,
    /// Linear grid index.
    pub voxel: usize,
    /// Depth from the heart: path length over the DMS, voxel units.
    pub depth: f64,
    /// Proximity group, numbered from 0 in order of the groups' first (lowest-position) member.
    pub group: usize,
}

/// The extreme points of `surface` for the depth labelling `depth` from the heart, ordered by
/// position.
///
/// A voxel is an extreme point when its depth is finite, positive, at least the depth of each
/// of its DMS 26-neighbours (a local maximum), and at least the depth of every DMS voxel within
/// [`PathOptions::extreme_neighbourhood`] voxels (a box, Chebyshev distance) of it. Points closer
/// than [`PathOptions::group_radius`] (Euclidean, voxel units) are grouped transitively.
pub fn extreme_points(
    surface: &MedialSurface,
    graph: &DmsGraph,
    depth: &[f64],
    options: &PathOptions,
) -> Vec<ExtremePoint> {
    let grid = &surface.grid;
    let reach = options.extreme_neighbourhood as i64;
    let mut points: Vec<ExtremePoint> = Vec::new();
    for p in 0..graph.len() {
        let d = depth[p];
        if !(d.is_finite() && d > 0.0) || graph.neighbours(p).any(|(q, _)| depth[q] > d) {
            continue;
        }
        let c = surface.coords(p);
        let mut deepest = true;
        'box_scan: for dz in -reach..=reach {
            for dy in -reach..=reach {
                for dx in -reach..=reach {
                    let offset = [dx as i32, dy as i32, dz as i32];
                    let Some(q) = grid.offset(c, offset).and_then(|i| surface.position(i)) else {
                        continue;
                    };
                    if depth[q].is_finite() && depth[q] > d {
                        deepest = false;
                        break 'box_scan;
                    }
                }
            }
        }
        if deepest {
            points.push(ExtremePoint {
                position: p,
                voxel: surface.voxels[p],
                depth: d,
                group: 0,
            });
        }
    }
    group(surface, &mut points, options.group_radius);
    points
}

/// Groups `points` transitively by Euclidean voxel distance `<= radius`.
fn group(surface: &MedialSurface, points: &mut [ExtremePoint], radius: f64) {
    let coords: Vec<[f64; 3]> = points
        .iter()
        .map(|e| surface.coords(e.position).map(|v| v as f64))
        .collect();
    let mut label: Vec<usize> = (0..points.len()).collect();
    fn find(label: &mut [usize], mut i: usize) -> usize {
        while label[i] != i {
            label[i] = label[label[i]];
            i = label[i];
        }
        i
    }
    let r2 = radius * radius;
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            let d2: f64 = (0..3).map(|a| (coords[i][a] - coords[j][a]).powi(2)).sum();
            if d2 <= r2 {
                let (a, b) = (find(&mut label, i), find(&mut label, j));
                // Keep the lower index as the representative.
                label[a.max(b)] = a.min(b);
            }
        }
    }
    let mut number = vec![usize::MAX; points.len()];
    let mut next = 0;
    for (i, point) in points.iter_mut().enumerate() {
        let root = find(&mut label, i);
        if number[root] == usize::MAX {
            number[root] = next;
            next += 1;
        }
        point.group = number[root];
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::surface;
    use super::super::{heart, DmsGraph};
    use super::*;

    #[test]
    fn a_plus_shape_has_four_extreme_points_in_four_groups() {
        let mut coords = Vec::new();
        for i in 1..30 {
            coords.push([i, 15, 2]);
            coords.push([15, i, 2]);
        }
        let s = surface([31, 31, 5], &coords, 4);
        let graph = DmsGraph::new(&s);
        let options = PathOptions::default();
        let h = heart(&graph, 0, &options);
        assert_eq!(s.coords(h.position), [15, 15, 2]);
        let points = extreme_points(&s, &graph, &h.depth, &options);
        assert_eq!(points.len(), 4);
        let groups: Vec<usize> = points.iter().map(|e| e.group).collect();
        assert_eq!(groups, vec![0, 1, 2, 3]);
        assert!(points.iter().all(|e| e.depth == 14.0));
    }
}
