//! Orthographic SVG projections of a mesh with predicted and reference skeletons and the error
//! vectors between paired joints. Pure string building.

use super::escape;
use crate::eval::{Evaluation, ReferenceRig};
use crate::mesh::Mesh;
use glam::{DVec2, DVec3};
use std::fmt::Write;

/// A view direction. Frames follow the refdata convention: +Y up, the figure faces +Z, its left
/// is +X.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// From the front (camera on +Z): screen right = +X (the figure's left), up = +Y.
    Front,
    /// From the figure's right side (camera on −X): screen right = +Z (forward), up = +Y.
    Side,
    /// From above (camera on +Y): screen right = −X, up = +Z (forward).
    Top,
}

impl View {
    /// All three views in page order.
    pub const ALL: [View; 3] = [View::Front, View::Side, View::Top];

    /// Screen right and screen up as world directions (right × up points at the camera).
    pub fn axes(self) -> (DVec3, DVec3) {
        match self {
            View::Front => (DVec3::X, DVec3::Y),
            View::Side => (DVec3::Z, DVec3::Y),
            View::Top => (DVec3::NEG_X, DVec3::Z),
        }
    }

    /// Lowercase name (`front`, `side`, `top`).
    pub fn name(self) -> &'static str {
        match self {
            View::Front => "front",
            View::Side => "side",
            View::Top => "top",
        }
    }

    fn project(self, p: DVec3) -> DVec2 {
        let (right, up) = self.axes();
        DVec2::new(p.dot(right), p.dot(up))
    }
}

/// Drawing options of [`projection_svg`] and the bar chart.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgOptions {
    /// Width of the drawing area, pixels. Default 360.
    pub width: f64,
    /// Empty border around the drawing, pixels. Default 12.
    pub margin: f64,
    /// Draw only triangles facing the camera (enough for the silhouette of a closed,
    /// outward-wound mesh; halves the file size). Default true.
    pub cull_back_faces: bool,
    /// Fill colour of the mesh silhouette. Default light grey.
    pub mesh_colour: String,
    /// Colour of predicted joints and bones. Default red.
    pub predicted_colour: String,
    /// Colour of reference joints and bones. Default blue.
    pub reference_colour: String,
    /// Colour of the error vectors (reference → predicted). Default dark orange.
    pub error_colour: String,
    /// Joint marker radius, pixels. Default 2.5.
    pub joint_radius: f64,
}

impl Default for SvgOptions {
    fn default() -> Self {
        Self {
            width: 360.0,
            margin: 12.0,
            cull_back_faces: true,
            mesh_colour: "#d9d9d9".into(),
            predicted_colour: "#d62728".into(),
            reference_colour: "#1f77b4".into(),
            error_colour: "#ff7f0e".into(),
            joint_radius: 2.5,
        }
    }
}

/// Maps projected coordinates to pixels (y down).
struct Frame {
    min: DVec2,
    max: DVec2,
    scale: f64,
    margin: f64,
}

impl Frame {
    fn new(points: impl Iterator<Item = DVec2>, options: &SvgOptions) -> Self {
        let (mut min, mut max) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for p in points.filter(|p| p.is_finite()) {
            min = min.min(p);
            max = max.max(p);
        }
        if !min.is_finite() {
            (min, max) = (DVec2::ZERO, DVec2::ONE);
        }
        let extent = (max - min).max_element();
        let inner = (options.width - 2.0 * options.margin).max(1.0);
        let scale = if extent > 0.0 { inner / extent } else { 1.0 };
        Self {
            min,
            max,
            scale,
            margin: options.margin,
        }
    }

    fn pixel(&self, p: DVec2) -> DVec2 {
        DVec2::new(
            self.margin + (p.x - self.min.x) * self.scale,
            self.margin + (self.max.y - p.y) * self.scale,
        )
    }

    fn size(&self) -> DVec2 {
        (self.max - self.min) * self.scale + DVec2::splat(2.0 * self.margin)
    }
}

/// One orthographic view as a standalone `<svg>` element: the mesh silhouette (filled projected
/// triangles), the reference skeleton, the predicted skeleton and an error vector from each
/// paired reference joint to its predicted joint. Joints carry `<title>` tooltips.
///
/// `predicted`/`reference` are drawn as given (pass [`ReferenceRig::deforming`] copies to hide
/// control joints); error vectors come from `evaluation`. Coordinates are rounded to 0.1 px.
pub fn projection_svg(
    view: View,
    mesh: Option<&Mesh>,
    predicted: &ReferenceRig,
    reference: &ReferenceRig,
    evaluation: &Evaluation,
    options: &SvgOptions,
) -> String {
    let mesh_points = mesh.into_iter().flat_map(|m| {
        m.triangles
            .iter()
            .flatten()
            .map(|&i| m.positions[i as usize])
    });
    let joint_points = predicted
        .skeleton
        .joints
        .iter()
        .chain(&reference.skeleton.joints)
        .map(|j| j.position);
    let frame = Frame::new(
        mesh_points.chain(joint_points).map(|p| view.project(p)),
        options,
    );
    let px = |p: DVec3| frame.pixel(view.project(p));
    let size = frame.size();
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" class="view" width="{:.0}" height="{:.0}" viewBox="0 0 {:.1} {:.1}" role="img" aria-label="{} view">"#,
        size.x.ceil(),
        size.y.ceil(),
        size.x,
        size.y,
        view.name()
    );
    let _ = write!(svg, "<title>{} view</title>", view.name());
    if let Some(mesh) = mesh {
        svg.push_str(&silhouette_path(view, mesh, &frame, options));
    }
    for (rig, colour, class) in [
        (reference, &options.reference_colour, "reference"),
        (predicted, &options.predicted_colour, "predicted"),
    ] {
        let _ = write!(
            svg,
            r#"<g class="{class}" stroke="{colour}" fill="{colour}" stroke-width="1.5" stroke-linecap="round">"#
        );
        for (a, b) in rig.bones() {
            let (a, b) = (px(a), px(b));
            let _ = write!(
                svg,
                r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}"/>"#,
                a.x, a.y, b.x, b.y
            );
        }
        for joint in &rig.skeleton.joints {
            let p = px(joint.position);
            let _ = write!(
                svg,
                r#"<circle cx="{:.1}" cy="{:.1}" r="{}" stroke="none"><title>{} {}</title></circle>"#,
                p.x,
                p.y,
                options.joint_radius,
                class,
                escape(&joint.name)
            );
        }
        svg.push_str("</g>");
    }
    let _ = write!(
        svg,
        r#"<g class="errors" stroke="{}" stroke-width="1.2">"#,
        options.error_colour
    );
    for joint in &evaluation.joints {
        let (a, b) = (px(joint.reference), px(joint.predicted));
        let _ = write!(
            svg,
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}"><title>{}: {:.4} ({:.2} %)</title></line>"#,
            a.x,
            a.y,
            b.x,
            b.y,
            escape(&joint.key),
            joint.error,
            joint.error_percent
        );
    }
    svg.push_str("</g></svg>");
    svg
}

/// The mesh as one filled `<path>` of projected triangles (each wound the same way, so the
/// non-zero fill rule paints their union).
fn silhouette_path(view: View, mesh: &Mesh, frame: &Frame, options: &SvgOptions) -> String {
    let mut d = String::new();
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t).map(|p| frame.pixel(view.project(p)));
        // Pixel y points down, so a camera-facing (counter-clockwise) triangle has negative area.
        let area = (b - a).perp_dot(c - a);
        if area == 0.0 || (options.cull_back_faces && area > 0.0) {
            continue;
        }
        let (b, c) = if area > 0.0 { (c, b) } else { (b, c) };
        let _ = write!(
            d,
            "M{:.1} {:.1}L{:.1} {:.1}L{:.1} {:.1}Z",
            a.x, a.y, b.x, b.y, c.x, c.y
        );
    }
    format!(
        r#"<path class="mesh" fill="{}" stroke="none" d="{d}"/>"#,
        options.mesh_colour
    )
}
