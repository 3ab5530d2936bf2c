//! Integration tests of the mesh stage.
