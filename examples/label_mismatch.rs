//! Where per-vertex labels disagree with the reference rig's regions: prints the confusion of
//! one model and writes a PNG with front, side and top views of its mesh vertices, the upper
//! row coloured by the reference region, the lower row by our label (mismatching vertices
//! drawn large).
//!
//! Run: `cargo run --release --example label_mismatch -- MODEL_DIR OUT.png`
//! (`MODEL_DIR` holds `mesh.obj` and `rig_game_engine.json` or `rig_gltf.json`).

use glam::DVec3;
use skelfit::anatomy::Side;
use skelfit::anatomy::{agreement, label, part_region, LabelPipelineOptions, Region};
use skelfit::eval::{load_skeleton, reference_regions};
use skelfit::mesh::load;
use std::path::PathBuf;

fn colour(r: Option<Region>) -> [u8; 3] {
    match r {
        None => [120, 120, 120],
        Some(Region::Trunk) => [90, 90, 220],
        Some(Region::Head) => [230, 60, 60],
        Some(Region::Tail) => [160, 60, 200],
        Some(Region::Fore(Some(Side::Left))) => [40, 190, 40],
        Some(Region::Fore(_)) => [20, 110, 20],
        Some(Region::Hind(Some(Side::Left))) => [240, 170, 30],
        Some(Region::Hind(_)) => [150, 100, 10],
        Some(Region::Wing(_)) => [30, 200, 200],
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 3 {
        eprintln!("usage: label_mismatch MODEL_DIR OUT.png");
        std::process::exit(2);
    }
    let dir = PathBuf::from(&args[1]);
    let mesh = load(&dir.join("mesh.obj")).expect("mesh");
    let rig = ["rig_game_engine.json", "rig_gltf.json"]
        .iter()
        .map(|n| dir.join(n))
        .find(|p| p.is_file())
        .expect("rig");
    let rig = load_skeleton(&rig).expect("rig");
    let labels = label(&mesh, &LabelPipelineOptions::default()).expect("label");
    let reference = reference_regions(&rig, &mesh);
    let a = agreement(&labels, &reference);
    println!("{:.1} % ({}/{})", a.percent, a.agreeing, a.compared);
    for (r, n, k) in &a.per_region {
        println!("  {r}: {k}/{n}");
    }
    for (r, o, n) in a.confusion.iter().take(12) {
        println!("  ref {r} → ours {o}: {n}");
    }
    let ours: Vec<Option<Region>> = labels
        .mesh_parts
        .iter()
        .map(|&p| Some(part_region(&labels, p as usize)))
        .collect();
    // Views: (horizontal axis, vertical axis).
    let views = [
        (DVec3::X, DVec3::Y),
        (DVec3::Z, DVec3::Y),
        (DVec3::X, DVec3::Z),
    ];
    let (lo, hi) = mesh.positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let extent = (hi - lo).max_element();
    let cell = 400usize;
    let (w, h) = (cell * 3, cell * 2);
    let mut img = vec![255u8; w * h * 3];
    let mut put = |x: i64, y: i64, c: [u8; 3]| {
        if x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h {
            let i = (y as usize * w + x as usize) * 3;
            img[i..i + 3].copy_from_slice(&c);
        }
    };
    for row in 0..2 {
        let regions = if row == 0 { &reference } else { &ours };
        for (col, &(u, v)) in views.iter().enumerate() {
            // Agreeing first, mismatching on top.
            for pass in 0..2 {
                for (i, &p) in mesh.positions.iter().enumerate() {
                    let mismatch = reference[i].is_some() && reference[i] != ours[i];
                    if (pass == 1) != mismatch {
                        continue;
                    }
                    let q = p - lo;
                    let x = (col * cell) as f64 + 10.0 + q.dot(u) / extent * (cell as f64 - 20.0);
                    let y =
                        ((row + 1) * cell) as f64 - 10.0 - q.dot(v) / extent * (cell as f64 - 20.0);
                    let r = if mismatch { 2 } else { 0 };
                    for dy in -r..=r {
                        for dx in -r..=r {
                            put(x as i64 + dx, y as i64 + dy, colour(regions[i]));
                        }
                    }
                }
            }
        }
    }
    let file = std::fs::File::create(&args[2]).expect("png");
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w as u32, h as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()
        .expect("png")
        .write_image_data(&img)
        .expect("png");
}
