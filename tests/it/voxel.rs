//! Integration tests of the voxel stage.
