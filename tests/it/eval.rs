//! Integration tests of the eval stage.
