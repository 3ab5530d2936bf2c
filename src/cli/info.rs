//! `skelfit info MESH [--json]`.

use super::common::load_mesh;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `skelfit info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// Mesh file (.obj, .gltf, .glb, .stl, .ply).
    pub mesh: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Prints the statistics of one mesh.
pub fn run(args: &InfoArgs) -> anyhow::Result<()> {
    let mesh = load_mesh(&args.mesh)?;
    let stats = mesh.stats();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&stats)?);
        return Ok(());
    }
    println!("mesh              {}", args.mesh.display());
    println!("vertices          {}", stats.vertices);
    println!("triangles         {}", stats.triangles);
    println!("components        {}", stats.components);
    println!("boundary edges    {}", stats.boundary_edges);
    println!("non-manifold edges {}", stats.non_manifold_edges);
    println!("closed            {}", stats.closed);
    println!("degenerate tris   {}", stats.degenerate_triangles);
    if let (Some(min), Some(max)) = (stats.bbox_min, stats.bbox_max) {
        println!("bounding box      {min:?} .. {max:?}");
    }
    println!("surface area      {:.6}", stats.surface_area);
    match stats.signed_volume {
        Some(v) => println!("signed volume     {v:.6}"),
        None => println!("signed volume     n/a (the mesh is not closed)"),
    }
    Ok(())
}
