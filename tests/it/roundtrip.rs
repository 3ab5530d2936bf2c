//! The user's file round-trips (issue 22): a rigged glTF/OBJ keeps its vertices, UVs,
//! normals, materials and images, adds only the skin, and draws the input in its rest pose.

use glam::DVec3;
use skelfit::export::{model_glb_bytes, GltfOptions, OutputFrame};
use skelfit::mesh::{load_gltf_scene, load_model, Mesh};
use skelfit::pipeline::{rig, RigOptions};
use std::path::{Path, PathBuf};

/// What a test reads back from a written GLB.
pub(crate) struct Written {
    pub json: serde_json::Value,
    pub vertices: usize,
    pub uvs: Vec<[f32; 2]>,
    pub weight_sums: Vec<f32>,
    pub image: Vec<u8>,
}

/// Reads the first primitive of every mesh of a GLB through the `gltf` crate.
pub(crate) fn read_written(bytes: &[u8]) -> Written {
    let gltf = gltf::Gltf::from_slice(bytes).expect("the output is valid glTF");
    let blob = gltf.blob.clone().expect("a binary chunk");
    let json: serde_json::Value =
        serde_json::from_slice(&gltf::Glb::from_slice(bytes).unwrap().json).unwrap();
    let mut written = Written {
        json,
        vertices: 0,
        uvs: Vec::new(),
        weight_sums: Vec::new(),
        image: Vec::new(),
    };
    for mesh in gltf.meshes() {
        for primitive in mesh.primitives() {
            let reader = primitive.reader(|_| Some(&blob[..]));
            written.vertices += reader.read_positions().unwrap().count();
            if let Some(uvs) = reader.read_tex_coords(0) {
                written.uvs.extend(uvs.into_f32());
            }
            written.weight_sums.extend(
                reader
                    .read_weights(0)
                    .expect("WEIGHTS_0")
                    .into_f32()
                    .map(|w| w.iter().sum::<f32>()),
            );
            assert!(reader.read_joints(0).is_some(), "JOINTS_0");
        }
    }
    if let Some(image) = gltf.images().next() {
        if let gltf::image::Source::View { view, .. } = image.source() {
            written.image = blob[view.offset()..view.offset() + view.length()].to_vec();
        }
    }
    written
}

/// A 2×2 PNG (red, green, blue, white).
fn small_png() -> Vec<u8> {
    // Generated once (zlib-compressed rows of RGB pixels, filter byte 0).
    vec![
        137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 2, 0, 0, 0, 2, 8, 2,
        0, 0, 0, 253, 212, 154, 115, 0, 0, 0, 18, 73, 68, 65, 84, 120, 156, 99, 248, 207, 192, 192,
        0, 194, 12, 255, 129, 0, 0, 31, 238, 5, 251, 11, 217, 104, 139, 0, 0, 0, 0, 73, 69, 78, 68,
        174, 66, 96, 130,
    ]
}

/// The bundled humanoid as a triangle soup glTF (three vertices per triangle, so every vertex
/// is split from its neighbours as exporters split UV seams) with normals, planar UVs, a
/// textured material, under a node that moves and scales it. Returns the JSON, the binary
/// buffer and the soup's vertex count.
fn textured_soup(mesh: &Mesh, image_uri: Option<&str>) -> (String, Vec<u8>, usize) {
    let (min, max) = mesh.bounding_box().unwrap();
    let size = max - min;
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for t in 0..mesh.triangles.len() {
        let corners = mesh.corners(t);
        let n = (corners[1] - corners[0])
            .cross(corners[2] - corners[0])
            .try_normalize()
            .unwrap_or(DVec3::Y);
        for p in corners {
            positions.push(p);
            normals.push(n);
            uvs.push([(p.x - min.x) / size.x, 1.0 - (p.y - min.y) / size.y]);
        }
    }
    let count = positions.len();
    let mut bin: Vec<u8> = Vec::new();
    let push3 = |bin: &mut Vec<u8>, v: &[DVec3]| {
        for p in v {
            for c in p.to_array() {
                bin.extend((c as f32).to_le_bytes());
            }
        }
    };
    push3(&mut bin, &positions);
    let normal_offset = bin.len();
    push3(&mut bin, &normals);
    let uv_offset = bin.len();
    for uv in &uvs {
        for c in uv {
            bin.extend((*c as f32).to_le_bytes());
        }
    }
    let image_offset = bin.len();
    let png = small_png();
    if image_uri.is_none() {
        bin.extend(&png);
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let image = match image_uri {
        Some(uri) => format!(r#"{{"uri": "{uri}"}}"#),
        None => r#"{"bufferView": 3, "mimeType": "image/png"}"#.to_string(),
    };
    let json = format!(
        r#"{{"asset": {{"version": "2.0", "generator": "test"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"name": "holder", "children": [1], "translation": [0.5, 0, 0], "scale": [2, 2, 2]}},
            {{"name": "body", "mesh": 0, "rotation": [0, 0.7071068, 0, 0.7071068]}}],
  "meshes": [{{"name": "body", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}}, "material": 0}}]}}],
  "materials": [{{"name": "skin", "pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}, "baseColorFactor": [0.8, 0.6, 0.5, 1]}}}}],
  "textures": [{{"source": 0, "sampler": 0}}],
  "samplers": [{{"magFilter": 9729}}],
  "images": [{image}],
  "buffers": [{{"byteLength": {len}}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": {normal_offset}, "target": 34962}},
                  {{"buffer": 0, "byteOffset": {normal_offset}, "byteLength": {normal_len}, "target": 34962}},
                  {{"buffer": 0, "byteOffset": {uv_offset}, "byteLength": {uv_len}, "target": 34962}},
                  {{"buffer": 0, "byteOffset": {image_offset}, "byteLength": {png_len}}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": {count}, "type": "VEC3",
                  "min": [{}, {}, {}], "max": [{}, {}, {}]}},
                {{"bufferView": 1, "componentType": 5126, "count": {count}, "type": "VEC3"}},
                {{"bufferView": 2, "componentType": 5126, "count": {count}, "type": "VEC2"}}]}}"#,
        min.x as f32,
        min.y as f32,
        min.z as f32,
        max.x as f32,
        max.y as f32,
        max.z as f32,
        len = bin.len(),
        normal_len = uv_offset - normal_offset,
        uv_len = image_offset - uv_offset,
        png_len = png.len(),
    );
    (json, bin, count)
}

fn bundled_humanoid() -> Mesh {
    skelfit::mesh::load(&crate::common::data_dir().join("humanoid/mh_neutral_default/mesh.obj"))
        .unwrap()
}

/// Rigs `path` through the library and writes the model back; returns the bytes, the welded
/// mesh it was rigged on.
fn rig_model(path: &Path, frame: &OutputFrame) -> (Vec<u8>, Mesh) {
    let (mesh, model) = load_model(path).unwrap();
    let model = model.expect("a glTF/OBJ model");
    let rigged = rig(&mesh, &RigOptions::default()).unwrap();
    let bytes = model_glb_bytes(
        &model,
        &rigged.fit.skeleton,
        &rigged.skin,
        frame,
        &GltfOptions::default(),
    )
    .unwrap();
    (bytes, mesh)
}

/// Every welded vertex of `a` within `tolerance` of a vertex of `b`, and as many (the output
/// may list them in another order: an OBJ's primitives follow its materials).
fn assert_same_positions(a: &Mesh, b: &Mesh, tolerance: f64) {
    assert_eq!(a.positions.len(), b.positions.len());
    let cell = |p: DVec3| (p / 1e-3).floor().as_ivec3().to_array();
    let mut grid: std::collections::HashMap<[i32; 3], Vec<DVec3>> = Default::default();
    for &q in &b.positions {
        grid.entry(cell(q)).or_default().push(q);
    }
    let mut worst = 0.0f64;
    for &p in &a.positions {
        let [x, y, z] = cell(p);
        let mut nearest = f64::INFINITY;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for q in grid.get(&[x + dx, y + dy, z + dz]).into_iter().flatten() {
                        nearest = nearest.min(p.distance(*q));
                    }
                }
            }
        }
        worst = worst.max(nearest);
    }
    assert!(worst <= tolerance, "rest pose moved a vertex by {worst}");
}

#[test]
fn rigged_textured_gltf_keeps_vertices_uvs_material_and_image() {
    let dir = tempfile::tempdir().unwrap();
    let (json, bin, count) = textured_soup(&bundled_humanoid(), None);
    let input = dir.path().join("soup.glb");
    std::fs::write(&input, crate::mesh::glb(&json, &bin)).unwrap();
    let (bytes, welded) = rig_model(&input, &OutputFrame::IDENTITY);
    let out = read_written(&bytes);
    assert_eq!(out.vertices, count, "one output vertex per input vertex");
    assert_eq!(out.uvs.len(), count, "TEXCOORD_0 kept");
    let first_uv = out.uvs[0];
    assert!(first_uv.iter().all(|c| (0.0..=1.0).contains(c)));
    assert_eq!(out.json["materials"][0]["name"], "skin");
    assert_eq!(
        out.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"],
        0
    );
    assert_eq!(
        out.image,
        small_png(),
        "the embedded image is kept byte for byte"
    );
    assert_eq!(
        out.json["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|n| n.get("skin").is_some())
            .count(),
        1
    );
    for (v, sum) in out.weight_sums.iter().enumerate() {
        assert!((sum - 1.0).abs() < 1e-5, "vertex {v}: weights sum to {sum}");
    }
    // The rest pose draws the input where the loader put it (node transforms applied).
    let path = dir.path().join("rigged.glb");
    std::fs::write(&path, &bytes).unwrap();
    let back = load_gltf_scene(&path).unwrap();
    assert_same_positions(&back.mesh, &welded, 1e-5);
    if let Some(report) = crate::export::validate(&[path]) {
        assert!(report.contains("numErrors=0 "), "{report}");
    }
}

#[test]
fn external_images_of_a_gltf_are_embedded_and_outside_ones_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = bundled_humanoid();
    let folder = dir.path().join("model");
    std::fs::create_dir(&folder).unwrap();
    std::fs::write(folder.join("skin.png"), small_png()).unwrap();
    std::fs::write(dir.path().join("outside.png"), small_png()).unwrap();
    for (uri, embedded) in [
        ("skin.png", true),
        ("../outside.png", false),
        ("/etc/passwd", false),
    ] {
        let (json, bin, _) = textured_soup(&mesh, Some(uri));
        let input = folder.join("soup.glb");
        std::fs::write(&input, crate::mesh::glb(&json, &bin)).unwrap();
        let (_, model) = load_model(&input).unwrap();
        let model = model.unwrap();
        let image = &model.document["images"][0];
        assert!(image.get("uri").is_none(), "{uri}: {image}");
        let view = image["bufferView"].as_u64().unwrap() as usize;
        let buffer = model.document["bufferViews"][view]["buffer"]
            .as_u64()
            .unwrap() as usize;
        let data = &model.buffers[buffer];
        if embedded {
            assert_eq!(data, &small_png());
            assert!(model
                .warnings
                .iter()
                .all(|w| !w.to_string().contains("image")));
        } else {
            assert_ne!(data, &small_png());
            assert!(
                model
                    .warnings
                    .iter()
                    .any(|w| w.to_string().contains("image 0") && w.to_string().contains("refused")),
                "{uri}: {:?}",
                model.warnings
            );
        }
    }
}

/// CesiumMan (`../shared/refdata`): 3,273 vertices, one material, one UV set, a JPEG texture,
/// skinned and animated; the rigged file keeps all of it but the old skin and animation, and
/// the Khronos validator reports no error.
#[test]
fn rigged_cesium_man_keeps_its_uvs_material_texture_and_vertices() {
    let Some(dir) = crate::common::model("humanoid/gltf_cesium_man") else {
        return;
    };
    let source: PathBuf = dir.join("source.glb");
    let (bytes, welded) = rig_model(&source, &OutputFrame::IDENTITY);
    let out = read_written(&bytes);
    assert_eq!(out.vertices, 3273);
    assert_eq!(out.uvs.len(), 3273);
    assert_eq!(out.json["materials"].as_array().unwrap().len(), 1);
    assert_eq!(out.json["images"].as_array().unwrap().len(), 1);
    assert!(
        out.image.starts_with(&[0xFF, 0xD8, 0xFF]),
        "the JPEG is embedded"
    );
    assert!(out.json.get("animations").is_none());
    for sum in &out.weight_sums {
        assert!((sum - 1.0).abs() < 1e-5);
    }
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("cesium_rigged.glb");
    std::fs::write(&path, &bytes).unwrap();
    let back = load_gltf_scene(&path).unwrap();
    assert_same_positions(&back.mesh, &welded, 1e-5);
    if let Some(report) = crate::export::validate(&[path]) {
        eprintln!("{report}");
        assert!(report.contains("numErrors=0 "), "{report}");
    }
}

/// An OBJ with a UV per corner (every vertex split), two `usemtl` materials and an MTL library
/// whose first material has a `map_Kd` image: the output has a vertex per distinct corner, a
/// primitive per material, both materials and the image.
#[test]
fn rigged_obj_keeps_uvs_and_mtl_materials_with_their_image() {
    use std::fmt::Write;
    let mesh = bundled_humanoid();
    let dir = tempfile::tempdir().unwrap();
    let (min, max) = mesh.bounding_box().unwrap();
    let mut obj = String::from("mtllib body.mtl\n");
    for p in &mesh.positions {
        writeln!(obj, "v {} {} {}", p.x, p.y, p.z).unwrap();
    }
    let half = mesh.triangles.len() / 2;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if t == 0 {
            obj.push_str("usemtl skin\n");
        } else if t == half {
            obj.push_str("usemtl cloth\n");
        }
        for &v in tri {
            let p = mesh.positions[v as usize];
            let u = (p.x - min.x) / (max.x - min.x);
            let w = (p.y - min.y) / (max.y - min.y) + t as f64 * 1e-9;
            writeln!(obj, "vt {u} {w}").unwrap();
        }
        writeln!(
            obj,
            "f {}/{} {}/{} {}/{}",
            tri[0] + 1,
            3 * t + 1,
            tri[1] + 1,
            3 * t + 2,
            tri[2] + 1,
            3 * t + 3
        )
        .unwrap();
    }
    std::fs::write(dir.path().join("body.obj"), obj).unwrap();
    std::fs::write(
        dir.path().join("body.mtl"),
        "newmtl skin\nKd 1 1 1\nmap_Kd textures/skin.png\nnewmtl cloth\nKd 0.2 0.3 0.4\n",
    )
    .unwrap();
    std::fs::create_dir(dir.path().join("textures")).unwrap();
    std::fs::write(dir.path().join("textures/skin.png"), small_png()).unwrap();
    let (bytes, welded) = rig_model(&dir.path().join("body.obj"), &OutputFrame::IDENTITY);
    let out = read_written(&bytes);
    let corners = 3 * mesh.triangles.len();
    assert_eq!(out.vertices, corners, "a vertex per distinct corner");
    assert_eq!(out.uvs.len(), corners);
    let primitives = out.json["meshes"][0]["primitives"].as_array().unwrap();
    assert_eq!(primitives.len(), 2);
    assert_eq!(primitives[1]["material"], 1);
    assert_eq!(out.json["materials"][1]["name"], "cloth");
    let factor = &out.json["materials"][1]["pbrMetallicRoughness"]["baseColorFactor"];
    assert_eq!(factor, &serde_json::json!([0.2, 0.3, 0.4, 1.0]));
    assert_eq!(
        out.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"],
        0
    );
    assert_eq!(out.image, small_png());
    for sum in &out.weight_sums {
        assert!((sum - 1.0).abs() < 1e-5);
    }
    let path = dir.path().join("rigged.glb");
    std::fs::write(&path, &bytes).unwrap();
    let back = load_gltf_scene(&path).unwrap();
    assert_same_positions(&back.mesh, &welded, 1e-5);
    if let Some(report) = crate::export::validate(&[path]) {
        assert!(report.contains("numErrors=0 "), "{report}");
    }
}
