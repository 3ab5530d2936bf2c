//! Integration tests of the distance stage.
