//! Bounds and type checks on glTF accessors before the `gltf` crate's readers touch them
//! (those readers index slices and assert on element sizes, so malformed files would panic).

use gltf::accessor::{Accessor, DataType, Dimensions};
use gltf::buffer::View;

/// Checks that `accessor` has one of `types`, the given `dimensions`, at least one element, and
/// that every byte it (and its sparse part) reads lies inside its buffer view and buffer.
/// `what` names the accessor in the message (e.g. "POSITION of mesh 0 primitive 1").
pub(super) fn check(
    accessor: &Accessor,
    buffers: &[&[u8]],
    types: &[DataType],
    dimensions: Dimensions,
    what: &str,
) -> Result<(), String> {
    let index = accessor.index();
    if !types.contains(&accessor.data_type()) || accessor.dimensions() != dimensions {
        return Err(format!(
            "{what} (accessor {index}) is {:?} {:?}, expected {dimensions:?} of {types:?}",
            accessor.dimensions(),
            accessor.data_type(),
        ));
    }
    let count = accessor.count();
    if count == 0 {
        return Err(format!("{what} (accessor {index}) has no elements"));
    }
    let element = accessor.size();
    if let Some(view) = accessor.view() {
        check_view(&view, accessor.offset(), count, element, buffers)
            .map_err(|m| format!("{what} (accessor {index}): {m}"))?;
    }
    if let Some(sparse) = accessor.sparse() {
        let sparse_count = sparse.count();
        if sparse_count == 0 || sparse_count > count {
            return Err(format!(
                "{what} (accessor {index}) has {sparse_count} sparse values for {count} elements"
            ));
        }
        let indices = sparse.indices();
        check_view(
            &indices.view(),
            indices.offset(),
            sparse_count,
            indices.index_type().size(),
            buffers,
        )
        .map_err(|m| format!("{what} (accessor {index}) sparse indices: {m}"))?;
        let values = sparse.values();
        check_view(
            &values.view(),
            values.offset(),
            sparse_count,
            element,
            buffers,
        )
        .map_err(|m| format!("{what} (accessor {index}) sparse values: {m}"))?;
    }
    Ok(())
}

/// Checks that `count` elements of `element` bytes from `offset` fit in `view` and the view
/// in its buffer.
fn check_view(
    view: &View,
    offset: usize,
    count: usize,
    element: usize,
    buffers: &[&[u8]],
) -> Result<(), String> {
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "byte stride {stride} is smaller than the element size {element}"
        ));
    }
    let buffer_len = buffers
        .get(view.buffer().index())
        .map_or(0, |buffer| buffer.len());
    let view_end = view.offset().checked_add(view.length());
    if !fits(view_end, buffer_len) {
        return Err(format!(
            "buffer view {} reaches past the end of buffer {} ({buffer_len} bytes)",
            view.index(),
            view.buffer().index()
        ));
    }
    let needed = stride
        .checked_mul(count - 1)
        .and_then(|n| n.checked_add(element))
        .and_then(|n| n.checked_add(offset));
    if !fits(needed, view.length()) {
        return Err(format!(
            "{count} elements do not fit in buffer view {} ({} bytes)",
            view.index(),
            view.length()
        ));
    }
    Ok(())
}

/// Whether an end offset computed with checked arithmetic exists and is at most `limit`.
fn fits(end: Option<usize>, limit: usize) -> bool {
    end.is_some_and(|end| end <= limit)
}
