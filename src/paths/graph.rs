//! The 26-connected adjacency of the DMS voxels as flat arrays.

use crate::medial::MedialSurface;

/// Adjacency of the DMS voxels (compressed sparse rows), indexed by DMS *position* (index into
/// [`MedialSurface::voxels`]). Built once so that the many searches of the path stage read
/// flat arrays instead of probing the grid.
#[derive(Debug, Clone)]
pub struct DmsGraph {
    /// `offsets[p]..offsets[p + 1]` is the range of position `p`'s neighbours in `targets`.
    offsets: Vec<u32>,
    /// Neighbour positions.
    targets: Vec<u32>,
    /// Centre distance to each neighbour, voxel units (1, sqrt 2 or sqrt 3).
    steps: Vec<f64>,
    /// Connected component of each position, numbered from 0 in order of smallest position.
    component: Vec<u32>,
    /// Size of each component.
    sizes: Vec<usize>,
}

impl DmsGraph {
    /// The adjacency of `surface` (26-neighbours that are DMS voxels) and its connected
    /// components. `O(26 n)` for `n` DMS voxels.
    pub fn new(surface: &MedialSurface) -> Self {
        let n = surface.len();
        let mut offsets = Vec::with_capacity(n + 1);
        let mut targets = Vec::with_capacity(n * 8);
        let mut steps = Vec::with_capacity(n * 8);
        offsets.push(0u32);
        for p in 0..n {
            for (q, step) in surface.neighbours(p) {
                targets.push(q as u32);
                steps.push(step);
            }
            offsets.push(targets.len() as u32);
        }
        let mut graph = Self {
            offsets,
            targets,
            steps,
            component: vec![u32::MAX; n],
            sizes: Vec::new(),
        };
        graph.label_components();
        graph
    }

    fn label_components(&mut self) {
        let mut stack = Vec::new();
        for start in 0..self.len() {
            if self.component[start] != u32::MAX {
                continue;
            }
            let label = self.sizes.len() as u32;
            self.component[start] = label;
            stack.push(start);
            let mut size = 0;
            while let Some(p) = stack.pop() {
                size += 1;
                for k in self.offsets[p] as usize..self.offsets[p + 1] as usize {
                    let q = self.targets[k] as usize;
                    if self.component[q] == u32::MAX {
                        self.component[q] = label;
                        stack.push(q);
                    }
                }
            }
            self.sizes.push(size);
        }
    }

    /// Number of DMS voxels.
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// True when the graph has no voxel.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The DMS neighbours of position `p` as `(position, centre distance in voxel units)`.
    #[inline]
    pub fn neighbours(&self, p: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let range = self.offsets[p] as usize..self.offsets[p + 1] as usize;
        self.targets[range.clone()]
            .iter()
            .zip(&self.steps[range])
            .map(|(&q, &s)| (q as usize, s))
    }

    /// Number of DMS neighbours of position `p`.
    pub fn degree(&self, p: usize) -> usize {
        (self.offsets[p + 1] - self.offsets[p]) as usize
    }

    /// Connected component of position `p` (numbered in order of smallest position).
    pub fn component(&self, p: usize) -> u32 {
        self.component[p]
    }

    /// Number of connected components.
    pub fn components(&self) -> usize {
        self.sizes.len()
    }

    /// The largest component (the lowest-numbered among equals), or `None` for an empty graph.
    pub fn largest_component(&self) -> Option<u32> {
        let mut best: Option<(usize, u32)> = None;
        for (c, &size) in self.sizes.iter().enumerate() {
            if best.is_none_or(|(s, _)| size > s) {
                best = Some((size, c as u32));
            }
        }
        best.map(|(_, c)| c)
    }

    /// Size of component `c`.
    pub fn component_size(&self, c: u32) -> usize {
        self.sizes[c as usize]
    }
}
