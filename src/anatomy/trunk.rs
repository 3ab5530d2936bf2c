//! The trunk of the level graph and the figure class its slope gives (dissertation ch.7.3.3).

use super::{FigureClass, Frame, LevelGraph, RuleOptions};
use crate::math::{major_axis_by_iteration, point_covariance};
use crate::medial::MedialSurface;
use glam::DVec3;

/// The trunk: the level graph's root, its major junctions and the tree paths joining them.
pub(super) struct Trunk {
    /// Whether each level-graph vertex belongs to the trunk.
    pub vertices: Vec<bool>,
    /// Whether the graph has a major junction (without one the figure has no limbs to label).
    pub has_junction: bool,
    /// The centres of the trunk vertices' DMS voxels, mesh units.
    pub points: Vec<DVec3>,
    /// Principal axis of `points` (unit; zero when they have no spread).
    pub axis: DVec3,
    /// Angle between the axis and up, degrees (`NaN` without an axis).
    pub angle: f64,
    /// Human-like (axis near up), animal-like (near horizontal) or unknown.
    pub figure: FigureClass,
}

impl Trunk {
    /// The mean of the trunk's points (the origin when there are none).
    pub fn centre(&self) -> DVec3 {
        if self.points.is_empty() {
            DVec3::ZERO
        } else {
            self.points.iter().sum::<DVec3>() / self.points.len() as f64
        }
    }

    /// Carries the trunk on from the nearest trunk vertex up the tree to `v` (a chest
    /// junction where short fore limbs leave, `fore_limbs.rs`): the vertices on the way join
    /// the trunk and their voxels its points. The axis, its angle and the figure class stay
    /// those of the major junctions' trunk, so adding the chest never changes the class.
    pub fn extend_to(&mut self, v: usize, graph: &LevelGraph, surface: &MedialSurface) {
        for a in graph.ancestors(v) {
            if self.vertices[a] {
                break;
            }
            self.vertices[a] = true;
            self.points
                .extend(graph.vertices[a].voxels.iter().map(|&p| surface.centre(p)));
        }
    }
}

/// The trunk of `graph` and the figure class from its slope against `frame.up`: human-like
/// within [`RuleOptions::vertical_angle`], animal-like beyond
/// [`RuleOptions::horizontal_angle`], unknown between them or without a major junction.
pub(super) fn trunk(
    graph: &LevelGraph,
    surface: &MedialSurface,
    frame: &Frame,
    options: &RuleOptions,
) -> Trunk {
    let n = graph.vertices.len();
    let mut vertices = vec![false; n];
    if n > 0 {
        vertices[graph.root] = true;
    }
    let junctions: Vec<usize> = (0..n)
        .filter(|&v| graph.vertices[v].major_junction)
        .collect();
    for &j in &junctions {
        for a in graph.ancestors(j) {
            if vertices[a] {
                break;
            }
            vertices[a] = true;
        }
    }
    let has_junction = !junctions.is_empty();
    let points: Vec<DVec3> = (0..n)
        .filter(|&v| vertices[v])
        .flat_map(|v| graph.vertices[v].voxels.iter().map(|&p| surface.centre(p)))
        .collect();
    let axis = principal_axis(&points);
    let angle = if axis == DVec3::ZERO {
        f64::NAN
    } else {
        axis.dot(frame.up).abs().min(1.0).acos().to_degrees()
    };
    let figure = if !has_junction || angle.is_nan() {
        FigureClass::Unknown
    } else if angle <= options.vertical_angle {
        FigureClass::HumanLike
    } else if angle >= options.horizontal_angle {
        FigureClass::AnimalLike
    } else {
        FigureClass::Unknown
    };
    Trunk {
        vertices,
        has_junction,
        points,
        axis,
        angle,
        figure,
    }
}

/// Principal axis (unit) of `points`: the major axis of their covariance
/// ([`major_axis_by_iteration`]); zero for fewer than two points or no spread.
fn principal_axis(points: &[DVec3]) -> DVec3 {
    if points.len() < 2 {
        return DVec3::ZERO;
    }
    let (_, covariance) = point_covariance(points);
    major_axis_by_iteration(covariance).unwrap_or(DVec3::ZERO)
}
