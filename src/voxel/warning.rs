//! What voxelization left out of the figure, and what the input mesh made uncertain.

use super::DroppedPiece;
use crate::warning::Severity;
use std::fmt;

/// Something voxelization could not take into the figure as it is.
#[derive(Debug, Clone, PartialEq)]
pub enum VoxelWarning {
    /// Connected pieces of the mesh lie apart from the figure and were left out of the voxels.
    LooseMeshPieces {
        /// How many pieces.
        pieces: usize,
        /// Their triangles.
        triangles: usize,
        /// Their share of the mesh's surface area, 0-1.
        area_share: f64,
    },
    /// Interior components too far apart from the figure to join it were dropped.
    DroppedInterior {
        /// The components dropped, largest first.
        pieces: Vec<DroppedPiece>,
        /// Their voxels.
        dropped_voxels: usize,
        /// Interior voxels before dropping them.
        interior_voxels: usize,
    },
    /// The mesh is not closed: inside/outside was decided by a winding-number vote.
    OpenMesh {
        /// Boundary edges.
        boundary_edges: usize,
        /// Non-manifold edges.
        non_manifold_edges: usize,
        /// Voxels whose votes disagreed.
        ambiguous_voxels: usize,
    },
    /// Thin, long pieces the figure holds (a sword, a staff) were left out of the voxels and
    /// are bound rigidly to the joint each touches.
    HeldProps {
        /// The pieces.
        props: Vec<super::Prop>,
    },
    /// Triangles repeating another one (the same three vertices) were counted once by the
    /// inside/outside vote.
    DuplicateTriangles {
        /// How many were left out of the vote.
        triangles: usize,
    },
}

impl VoxelWarning {
    /// How much it matters: dropped pieces are missing from the figure.
    pub fn severity(&self) -> Severity {
        match self {
            Self::LooseMeshPieces { .. } | Self::DroppedInterior { .. } => Severity::PartMissing,
            Self::OpenMesh { .. } | Self::DuplicateTriangles { .. } | Self::HeldProps { .. } => {
                Severity::Info
            }
        }
    }

    /// A stable snake_case id of the variant.
    pub fn code(&self) -> &'static str {
        match self {
            Self::LooseMeshPieces { .. } => "loose_mesh_pieces",
            Self::DroppedInterior { .. } => "dropped_interior",
            Self::OpenMesh { .. } => "open_mesh",
            Self::DuplicateTriangles { .. } => "duplicate_triangles",
            Self::HeldProps { .. } => "held_props",
        }
    }
}

/// `one` for a single item, else `many`.
fn number<'a>(count: usize, one: &'a str, many: &'a str) -> &'a str {
    if count == 1 {
        one
    } else {
        many
    }
}

impl fmt::Display for VoxelWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::LooseMeshPieces {
                pieces,
                triangles,
                area_share,
            } => write!(
                f,
                "{} loose piece{} of the mesh ({} triangles, {:.2} % of the surface area) {} apart \
                 from the figure and {} left out of the voxels (delete them from the mesh if they \
                 are not part of the figure)",
                pieces,
                number(*pieces, "", "s"),
                triangles,
                100.0 * area_share,
                number(*pieces, "lies", "lie"),
                number(*pieces, "was", "were")
            ),
            Self::DroppedInterior {
                pieces,
                dropped_voxels,
                interior_voxels,
            } => {
                let named: Vec<String> = pieces
                    .iter()
                    .take(3)
                    .map(|p| {
                        format!(
                            "{} voxels around ({:.3}, {:.3}, {:.3})",
                            p.voxels, p.centre[0], p.centre[1], p.centre[2]
                        )
                    })
                    .collect();
                let more = pieces.len().saturating_sub(named.len());
                let n = pieces.len();
                write!(
                    f,
                    "{} piece{} of the interior ({} voxels, {:.1} % of the interior) {} too far apart \
                     from the figure to join it and {} dropped: {}{} (raise the join gap if {} part of \
                     the figure, or delete {} from the mesh)",
                    n,
                    number(n, "", "s"),
                    dropped_voxels,
                    100.0 * *dropped_voxels as f64 / (*interior_voxels).max(1) as f64,
                    number(n, "lies", "lie"),
                    number(n, "was", "were"),
                    named.join(", "),
                    if more > 0 {
                        format!(" and {more} more")
                    } else {
                        String::new()
                    },
                    number(n, "it is", "they are"),
                    number(n, "it", "them"),
                )
            }
            Self::OpenMesh {
                boundary_edges,
                non_manifold_edges,
                ambiguous_voxels,
            } => write!(
                f,
                "the mesh is not closed ({boundary_edges} boundary, {non_manifold_edges} non-manifold edges): inside/outside was decided by a six-direction winding-number vote ({ambiguous_voxels} voxels had disagreeing votes)"
            ),
            Self::HeldProps { props } => {
                let named: Vec<String> = props
                    .iter()
                    .map(|p| {
                        format!(
                            "{:.3} long and {:.3} wide around ({:.3}, {:.3}, {:.3})",
                            p.length, p.width, p.centre[0], p.centre[1], p.centre[2]
                        )
                    })
                    .collect();
                write!(
                    f,
                    "{} thin rigid piece{} held by the figure (a sword, a staff: a separate piece at least \
                     8 times as long as wide with no mirrored twin) {} out of the skeleton fit and \
                     bound rigidly to the joint {} touches: {}",
                    props.len(),
                    number(props.len(), "", "s"),
                    number(props.len(), "is left", "are left"),
                    number(props.len(), "it", "each"),
                    named.join("; ")
                )
            }
            Self::DuplicateTriangles { triangles } => write!(
                f,
                "{} triangle{} repeat{} another one (the same three vertices): counted once for \
                 inside/outside (a doubled face would count twice and carve the figure); the mesh \
                 is skinned as given",
                triangles,
                number(*triangles, "", "s"),
                number(*triangles, "s", "")
            ),
        }
    }
}
