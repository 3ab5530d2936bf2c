//! Wavefront MTL material libraries: the few statements a glTF material can hold.

use super::model::ModelWarning;
use std::path::Path;

/// A material of an MTL file, as far as glTF's metallic-roughness model takes it.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct MtlMaterial {
    /// `newmtl` name.
    pub name: String,
    /// `Kd r g b`, linear 0-1.
    pub diffuse: Option<[f64; 3]>,
    /// `d a`, or `1 - t` from `Tr t`.
    pub alpha: Option<f64>,
    /// `map_Kd [options] file`: the file name (the statement's last word).
    pub diffuse_map: Option<String>,
    /// `Pm m` (PBR extension of MTL).
    pub metallic: Option<f64>,
    /// `Pr r` (PBR extension of MTL).
    pub roughness: Option<f64>,
}

/// The materials of every `mtllib` file named in the OBJ at `obj`, read only inside the OBJ's
/// folder (a refused or missing library is a warning); later definitions of a name come after
/// earlier ones, and lookups take the first.
pub(super) fn read_libraries(
    libraries: &[String],
    obj: &Path,
    warnings: &mut Vec<ModelWarning>,
) -> Vec<MtlMaterial> {
    let mut materials = Vec::new();
    for name in libraries {
        let text = super::gltf_buffers::folder_of(obj)
            .and_then(|folder| super::gltf_buffers::resolve_file(name, &folder))
            .and_then(|target| super::gltf_buffers::read_at_most(&target, MAX_MTL_BYTES))
            .and_then(|bytes| {
                String::from_utf8(bytes).map_err(|_| "is not text (invalid UTF-8)".to_string())
            });
        match text {
            Ok(text) => materials.extend(parse_mtl(&text)),
            Err(reason) => warnings.push(ModelWarning::LibraryUnreadable {
                name: name.to_string(),
                reason,
            }),
        }
    }
    materials
}

/// Largest material library read, bytes.
const MAX_MTL_BYTES: u64 = 16 << 20;

/// The materials of MTL text; statements other than `newmtl`, `Kd`, `d`, `Tr`, `map_Kd`, `Pm`
/// and `Pr` are ignored, unreadable numbers leave the value unset.
pub(super) fn parse_mtl(text: &str) -> Vec<MtlMaterial> {
    let mut materials: Vec<MtlMaterial> = Vec::new();
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let rest: Vec<&str> = words.collect();
        let number = |k: usize| rest.get(k).and_then(|w| w.parse::<f64>().ok());
        if keyword == "newmtl" {
            materials.push(MtlMaterial {
                name: rest.join(" "),
                ..Default::default()
            });
            continue;
        }
        let Some(m) = materials.last_mut() else {
            continue;
        };
        match keyword {
            "Kd" => {
                if let (Some(r), Some(g), Some(b)) = (number(0), number(1), number(2)) {
                    m.diffuse = Some([r, g, b]);
                }
            }
            "d" => m.alpha = number(0).or(m.alpha),
            "Tr" => m.alpha = number(0).map(|t| 1.0 - t).or(m.alpha),
            "Pm" => m.metallic = number(0),
            "Pr" => m.roughness = number(0),
            "map_Kd" => m.diffuse_map = rest.last().map(|f| f.replace('\\', "/")),
            _ => {}
        }
    }
    materials
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mtl_statements_become_fields() {
        let text = "# c\nnewmtl skin\nKd 0.8 0.6 0.5\nd 0.5\nmap_Kd -s 1 1 1 tex/skin.png\n\
                    newmtl eyes\nTr 0.25\nPm 0.1\nPr 0.4\n";
        let m = parse_mtl(text);
        assert_eq!(m.len(), 2);
        assert_eq!(m[0].name, "skin");
        assert_eq!(m[0].diffuse, Some([0.8, 0.6, 0.5]));
        assert_eq!(m[0].alpha, Some(0.5));
        assert_eq!(m[0].diffuse_map.as_deref(), Some("tex/skin.png"));
        assert_eq!(m[1].alpha, Some(0.75));
        assert_eq!((m[1].metallic, m[1].roughness), (Some(0.1), Some(0.4)));
    }
}
