//! The models of a batch: the mesh files of a folder (recursively) or of a list file, in a
//! stable sorted order, each with a unique output name.

use anyhow::{bail, Context};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Component, Path, PathBuf};

/// The mesh file extensions `skelfit rig` reads (case-insensitive).
pub const MESH_EXTENSIONS: [&str; 5] = ["obj", "glb", "gltf", "stl", "ply"];

/// In a folder holding this file, it is the only mesh taken: refdata's model folders hold the
/// artist's `source.glb` (UVs, materials, textures, which the rig's .glb keeps) beside a
/// converted `mesh.obj` of the same figure.
pub const PREFERRED: &str = "source.glb";

/// One model of a batch.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Model {
    /// Unique output name: a relative path with `/` separators (the output folder below
    /// `OUT/models/`).
    pub name: String,
    /// The mesh file relative to the batch's folder (or the list's folder), `/` separators;
    /// what the log and the report show, and the sort key.
    pub relative: String,
    /// The file to read.
    pub path: PathBuf,
}

/// True when `path` has one of [`MESH_EXTENSIONS`].
pub fn is_mesh(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| MESH_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

/// The models of `input`: a folder (every mesh file below it, hidden files and folders and
/// `skip` left out; in a folder holding [`PREFERRED`] only that file) or a list file (one
/// mesh path a line, relative to the list's folder; blank lines and lines starting with `#`
/// ignored). Sorted by relative path, duplicates removed, names made unique.
///
/// # Errors
/// `input` cannot be read, is a mesh file itself, or holds no model.
pub fn find_models(input: &Path, skip: Option<&Path>) -> anyhow::Result<Vec<Model>> {
    let files = if input.is_dir() {
        let skip = skip.and_then(|s| s.canonicalize().ok());
        let mut files = Vec::new();
        walk(input, &[], skip.as_deref(), &mut files)?;
        files
    } else if input.is_file() {
        if is_mesh(input) {
            bail!(
                "{} is a mesh file: batch takes a folder of meshes or a list file (one path a line); rig one mesh with `skelfit rig`",
                input.display()
            );
        }
        read_list(input)?
    } else {
        bail!("{}: no such folder or list file", input.display());
    };
    if files.is_empty() {
        bail!(
            "{} holds no mesh file ({})",
            input.display(),
            MESH_EXTENSIONS.map(|e| format!(".{e}")).join(", ")
        );
    }
    Ok(named(files))
}

/// A mesh file found: its relative path components and the path to read.
type Found = (Vec<String>, PathBuf);

/// Collects the mesh files of `dir` (relative components `prefix`) and of its sub-folders.
/// Symbolic links to files are followed, links to folders are not (no cycles).
fn walk(
    dir: &Path,
    prefix: &[String],
    skip: Option<&Path>,
    out: &mut Vec<Found>,
) -> anyhow::Result<()> {
    if skip.is_some_and(|s| dir.canonicalize().is_ok_and(|d| d == s)) {
        return Ok(());
    }
    let entries = std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))?;
    let mut meshes = Vec::new();
    let mut folders = Vec::new();
    for entry in entries {
        let entry = entry.with_context(|| format!("reading {}", dir.display()))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let path = entry.path();
        let kind = entry.file_type()?;
        if kind.is_dir() {
            folders.push((name, path));
        } else if (kind.is_file() || (kind.is_symlink() && path.is_file())) && is_mesh(&path) {
            meshes.push((name, path));
        }
    }
    if meshes.iter().any(|(name, _)| name == PREFERRED) {
        meshes.retain(|(name, _)| name == PREFERRED);
    }
    for (name, path) in meshes {
        let mut relative = prefix.to_vec();
        relative.push(name);
        out.push((relative, path));
    }
    for (name, path) in folders {
        let mut relative = prefix.to_vec();
        relative.push(name);
        walk(&path, &relative, skip, out)?;
    }
    Ok(())
}

/// The paths of a list file, resolved against its folder.
fn read_list(list: &Path) -> anyhow::Result<Vec<Found>> {
    let text = std::fs::read_to_string(list)
        .with_context(|| format!("reading list {}", list.display()))?;
    let folder = list.parent().unwrap_or(Path::new(""));
    Ok(text
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty() && !line.starts_with('#'))
        .map(|line| {
            let given = Path::new(line);
            let mut names = components(given);
            if names.is_empty() {
                // `.` or `/`: not a mesh file; it fails to load and is named `_`.
                names.push("_".into());
            }
            (names, folder.join(given))
        })
        .collect())
}

/// A path's components as names for the output: the root and `.` dropped, `..` as `_up`
/// (so that no output name leaves the output folder).
fn components(path: &Path) -> Vec<String> {
    path.components()
        .filter_map(|c| match c {
            Component::Normal(name) => Some(name.to_string_lossy().into_owned()),
            Component::ParentDir => Some("_up".to_string()),
            Component::CurDir | Component::RootDir | Component::Prefix(_) => None,
        })
        .collect()
}

/// Sorted, deduplicated models with unique names: the relative path without its extension
/// (`props/chair` for `props/chair.obj`), except that refdata's `mesh.*` and `source.*` are
/// named after their folder (`humanoid/mh_neutral_default`). A name given twice gets `-2`,
/// `-3`, ... in sorted order.
fn named(files: Vec<Found>) -> Vec<Model> {
    let files: BTreeMap<String, (Vec<String>, PathBuf)> = files
        .into_iter()
        .map(|(relative, path)| (relative.join("/"), (relative, path)))
        .collect();
    let mut taken = BTreeSet::new();
    files
        .into_iter()
        .map(|(key, (relative, path))| {
            let (file, folder) = relative.split_last().unwrap_or((&key, &[]));
            let stem = Path::new(file)
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let base = if !folder.is_empty() && GENERIC_STEMS.contains(&stem.as_str()) {
                folder.join("/")
            } else {
                folder
                    .iter()
                    .cloned()
                    .chain(std::iter::once(stem))
                    .collect::<Vec<_>>()
                    .join("/")
            };
            let mut name = base.clone();
            let mut n = 1;
            while !taken.insert(name.clone()) {
                n += 1;
                name = format!("{base}-{n}");
            }
            Model {
                name,
                relative: key,
                path,
            }
        })
        .collect()
}

/// File stems that name no model (refdata's `<model>/mesh.obj` and `<model>/source.glb`): such
/// a file's model is named after its folder.
const GENERIC_STEMS: [&str; 2] = ["mesh", "source"];

#[cfg(test)]
mod tests {
    use super::*;

    fn found(paths: &[&str]) -> Vec<Found> {
        paths
            .iter()
            .map(|p| (components(Path::new(p)), PathBuf::from(p)))
            .collect()
    }

    #[test]
    fn names_are_folders_or_stems_and_unique() {
        let models = named(found(&[
            "b/one/mesh.obj",
            "a.obj",
            "a.ply",
            "c/x.obj",
            "c/y.stl",
            "c/mesh.obj",
            "../up/z.obj",
        ]));
        let names: Vec<(&str, &str)> = models
            .iter()
            .map(|m| (m.relative.as_str(), m.name.as_str()))
            .collect();
        assert_eq!(
            names,
            vec![
                ("_up/up/z.obj", "_up/up/z"),
                ("a.obj", "a"),
                ("a.ply", "a-2"),
                ("b/one/mesh.obj", "b/one"),
                ("c/mesh.obj", "c"),
                ("c/x.obj", "c/x"),
                ("c/y.stl", "c/y"),
            ]
        );
    }
}
