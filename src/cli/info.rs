//! `skelfit info MESH [--json]` (`--json`: the statistics as JSON on stdout).

use super::common::{load_mesh, say};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `skelfit info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// Mesh file (.obj, .gltf, .glb, .stl, .ply).
    pub mesh: PathBuf,
}

/// Prints the statistics of one mesh.
pub fn run(args: &InfoArgs) -> anyhow::Result<()> {
    let mesh = load_mesh(&args.mesh)?;
    let stats = mesh.stats();
    if super::common::json_mode() {
        return super::common::print_json(&stats);
    }
    say!("mesh              {}", args.mesh.display());
    say!("vertices          {}", stats.vertices);
    say!("triangles         {}", stats.triangles);
    say!("components        {}", stats.components);
    say!("boundary edges    {}", stats.boundary_edges);
    say!("non-manifold edges {}", stats.non_manifold_edges);
    say!("closed            {}", stats.closed);
    say!("degenerate tris   {}", stats.degenerate_triangles);
    if let (Some(min), Some(max)) = (stats.bbox_min, stats.bbox_max) {
        say!("bounding box      {min:?} .. {max:?}");
    }
    say!("surface area      {:.6}", stats.surface_area);
    match stats.signed_volume {
        Some(v) => say!("signed volume     {v:.6}"),
        None => say!("signed volume     n/a (the mesh is not closed)"),
    }
    Ok(())
}
