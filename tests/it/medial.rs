//! Integration tests of the medial stage.
