//! Unit tests of the report stage.

use super::*;
use crate::eval::{evaluate, EvalOptions, ReferenceRig};
use crate::mesh::Mesh;
use crate::skeleton::{Canonical, Joint, JointId, Skeleton};
use glam::DVec3;

fn rigs() -> (ReferenceRig, ReferenceRig) {
    let joint = |name: &str, parent: Option<usize>, p: [f64; 3]| Joint {
        name: name.into(),
        parent: parent.map(JointId),
        position: DVec3::from_array(p),
        deform: true,
        ..Default::default()
    };
    let reference = Skeleton {
        joints: vec![
            joint(Canonical::Pelvis.as_str(), None, [0.0, 1.0, 0.0]),
            joint(Canonical::Neck.as_str(), Some(0), [0.0, 1.5, 0.0]),
            joint(Canonical::Head.as_str(), Some(1), [0.0, 1.7, 0.0]),
            joint("shoulder_<L>", Some(1), [0.2, 1.45, 0.0]),
        ],
    };
    let mut predicted = reference.clone();
    predicted.joints[2].position.z += 0.05;
    (
        ReferenceRig::from_skeleton("guess", predicted),
        ReferenceRig::from_skeleton("truth & co", reference),
    )
}

#[test]
fn html_report_is_self_contained_and_complete() {
    let (predicted, reference) = rigs();
    let mesh = Mesh::cuboid(DVec3::new(-0.3, 0.0, -0.2), DVec3::new(0.3, 1.8, 0.2));
    let evaluation =
        evaluate(&predicted, &reference, Some(&mesh), &EvalOptions::default()).unwrap();
    let input = ReportInput {
        evaluation: &evaluation,
        predicted: &predicted,
        reference: &reference,
        mesh: Some(&mesh),
    };
    let html = html_report(&input, &ReportOptions::default());
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert_eq!(html.matches("<svg").count(), 4, "three views and one chart");
    assert!(html.contains("truth &amp; co"));
    assert!(!html.contains("truth & co"));
    assert!(html.contains("shoulder_&lt;L&gt;"));
    // No external resources.
    for needle in ["<script", "<link", "src=", "@import", "url("] {
        assert!(!html.contains(needle), "{needle}");
    }
    assert!(!html
        .replace("http://www.w3.org/2000/svg", "")
        .contains("http"));
    // Per-joint table row for the offset joint.
    assert!(html.contains("<td>head</td><td>head</td><td>head</td><td class=\"n\">0.0500</td>"));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("report.html");
    write_html_report(&path, &input, &ReportOptions::default()).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), html);
    let err = write_html_report(
        &dir.path().join("no/such/dir.html"),
        &input,
        &ReportOptions::default(),
    )
    .unwrap_err();
    assert!(err.to_string().contains("dir.html"));
}

#[test]
fn projections_place_joints_by_view() {
    let (predicted, reference) = rigs();
    let evaluation = evaluate(&predicted, &reference, None, &EvalOptions::default()).unwrap();
    let options = SvgOptions::default();
    let front = projection_svg(
        View::Front,
        None,
        &predicted,
        &reference,
        &evaluation,
        &options,
    );
    let side = projection_svg(
        View::Side,
        None,
        &predicted,
        &reference,
        &evaluation,
        &options,
    );
    // One error vector per paired joint, one circle per joint of each skeleton.
    assert_eq!(front.matches("<circle").count(), 8);
    assert_eq!(front.matches("class=\"errors\"").count(), 1);
    // The head moved along +Z only: its error vector has zero length seen from the front and
    // is horizontal seen from the side.
    let errors = |svg: &str| svg[svg.find("class=\"errors\"").unwrap()..].to_owned();
    let f = errors(&front);
    let s = errors(&side);
    let head = |svg: &str| {
        let i = svg.find("<title>head:").unwrap();
        let line = &svg[svg[..i].rfind("<line").unwrap()..i];
        let number = |attr: &str| -> f64 {
            let start = line.find(attr).unwrap() + attr.len() + 2;
            line[start..start + line[start..].find('"').unwrap()]
                .parse()
                .unwrap()
        };
        (number("x1"), number("y1"), number("x2"), number("y2"))
    };
    let (x1, y1, x2, y2) = head(&f);
    assert_eq!((x1, y1), (x2, y2));
    let (x1, y1, x2, y2) = head(&s);
    assert_eq!(y1, y2);
    assert!(x2 > x1, "forward (+Z) is to the right in the side view");
}

#[test]
fn silhouette_culls_back_faces() {
    let (predicted, reference) = rigs();
    let evaluation = evaluate(&predicted, &reference, None, &EvalOptions::default()).unwrap();
    let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
    let count = |cull: bool| {
        let options = SvgOptions {
            cull_back_faces: cull,
            ..Default::default()
        };
        let svg = projection_svg(
            View::Front,
            Some(&mesh),
            &predicted,
            &reference,
            &evaluation,
            &options,
        );
        svg.matches('M').count()
    };
    // Seen from the front only the +z face's two triangles face the camera; side faces are
    // edge-on (zero area) and dropped either way.
    assert_eq!(count(true), 2);
    assert_eq!(count(false), 4);
}

#[test]
fn bar_chart_has_a_bar_per_joint() {
    let (predicted, reference) = rigs();
    let evaluation = evaluate(&predicted, &reference, None, &EvalOptions::default()).unwrap();
    let svg = error_bar_chart(&evaluation, &ChartOptions::default());
    assert_eq!(svg.matches("<rect").count(), evaluation.joints.len());
    assert!(svg.contains("stroke-dasharray"));
}

#[test]
fn escape_special_characters() {
    assert_eq!(escape("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
}

#[test]
fn line_chart_sorts_points_and_draws_every_series() {
    let series = vec![
        Series {
            name: "a".into(),
            colour: "#f00".into(),
            points: vec![(1.0, 0.0), (0.1, 2.0), (2.0, 1.0)],
        },
        Series {
            name: "b & c".into(),
            colour: "#00f".into(),
            points: vec![(0.1, 1.0)],
        },
    ];
    let svg = line_chart(
        &series,
        &LineChartOptions {
            log_x: true,
            ..Default::default()
        },
    );
    assert_eq!(svg.matches("<polyline").count(), 2);
    assert!(svg.contains("b &amp; c"));
    // Sorted by x: the leftmost point (x = 0.1) comes first, at the left edge of the plot.
    let points = svg.split("points=\"").nth(1).unwrap();
    assert!(points.starts_with("56.0,"), "{points}");
    let bars = bar_chart(
        &[("m".into(), 2.0), ("n".into(), 1.0)],
        "cap",
        &ChartOptions::default(),
    );
    assert_eq!(bars.matches("<rect").count(), 2);
}

#[test]
fn eval_pages_open_with_a_verdict_naming_the_worst_joint() {
    let (predicted, reference) = rigs();
    let mesh = Mesh::cuboid(DVec3::new(-0.3, 0.0, -0.2), DVec3::new(0.3, 1.8, 0.2));
    let evaluation =
        evaluate(&predicted, &reference, Some(&mesh), &EvalOptions::default()).unwrap();
    let verdict = eval_verdict(&evaluation);
    // The head is 5 cm off on a 1.8 tall figure (2.8 % of height), pelvis and neck exact: the
    // mean over the three canonical joints is 0.93 %.
    assert!(
        verdict.starts_with("good: mean joint error 0.93 % of height over 3 paired joints"),
        "{verdict}"
    );
    assert!(verdict.contains("worst: head 2.8 %"), "{verdict}");
    let html = html_report(
        &ReportInput {
            evaluation: &evaluation,
            predicted: &predicted,
            reference: &reference,
            mesh: Some(&mesh),
        },
        &ReportOptions::default(),
    );
    assert!(html.contains(&format!(
        "<p class=\"verdict\"><strong>Verdict:</strong> {}</p>",
        escape(&verdict)
    )));
}
