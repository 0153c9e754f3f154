//! Accessors read with every byte range checked first: the buffer view
//! inside its buffer, each element inside its view, a sparse accessor's
//! indices inside its count, and the count itself within the limits, so
//! that no file, however it lies, makes a read go past its data or an
//! allocation beyond what the limits allow.

use gltf::accessor::{DataType, Dimensions};
use gltf::buffer::View;

use super::{Fault, GltfProblem};

/// A problem with accessor `index`.
fn fault(index: usize, problem: String) -> Fault {
    (format!("accessors[{index}]"), GltfProblem::Accessor(problem))
}

/// The bytes `count` elements of `size` bytes take from `offset` in
/// `view` (at the view's stride, or packed), and that stride.
fn span<'b>(
    buffers: &'b [Vec<u8>],
    view: &View<'_>,
    (offset, count, size): (usize, usize, usize),
    index: usize,
) -> Result<(&'b [u8], usize), Fault> {
    let buffer = buffers.get(view.buffer().index()).map_or(&[][..], Vec::as_slice);
    let at = format!("bufferViews[{}]", view.index());
    let within = view.offset().checked_add(view.length()).and_then(|end| buffer.get(view.offset()..end));
    let bytes = within.ok_or_else(|| {
        let problem = format!(
            "bytes {}..+{} are past buffers[{}]'s {} bytes",
            view.offset(),
            view.length(),
            view.buffer().index(),
            buffer.len()
        );
        (at.clone(), GltfProblem::Buffer(problem))
    })?;
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err((at, GltfProblem::Buffer(format!("a stride of {stride} bytes is less than an element's {size}"))));
    }
    let end = count
        .checked_sub(1)
        .and_then(|last| last.checked_mul(stride))
        .and_then(|b| b.checked_add(size))
        .and_then(|b| b.checked_add(offset));
    match end {
        Some(end) if end <= bytes.len() => Ok((&bytes[offset..end], stride)),
        _ => Err(fault(
            index,
            format!(
                "{count} elements of {size} bytes from byte {offset} at a stride of {stride} run past {at}'s {} bytes",
                bytes.len()
            ),
        )),
    }
}

/// Accessor `a`'s elements, each its `size` bytes read by `read`, with a
/// sparse accessor's substitutions made; at most `max` of them.
fn elements<T: Copy + Default>(
    buffers: &[Vec<u8>],
    a: &gltf::Accessor<'_>,
    (size, max): (usize, usize),
    read: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, Fault> {
    let (index, count) = (a.index(), a.count());
    if count == 0 || count > max {
        return Err(fault(index, format!("a count of {count} elements is outside 1..={max}, what the limits allow")));
    }
    let mut out = match a.view() {
        Some(view) => {
            let (bytes, stride) = span(buffers, &view, (a.offset(), count, size), index)?;
            (0..count).map(|k| read(&bytes[k * stride..k * stride + size])).collect()
        }
        // No view: zeros, which a sparse accessor then replaces in part.
        None => vec![T::default(); count],
    };
    if let Some(sparse) = a.sparse() {
        let n = sparse.count();
        if n == 0 || n > count {
            return Err(fault(index, format!("sparse.count {n} is outside 1..={count}")));
        }
        let (indices, values) = (sparse.indices(), sparse.values());
        let width = indices.index_type().size();
        let (at, _) = span(buffers, &indices.view(), (indices.offset(), n, width), index)?;
        let (vals, _) = span(buffers, &values.view(), (values.offset(), n, size), index)?;
        for k in 0..n {
            let target = index_at(&at[k * width..(k + 1) * width]) as usize;
            let slot = out.get_mut(target).ok_or_else(|| {
                fault(index, format!("sparse entry {k}'s index is past the accessor's {count} elements"))
            })?;
            *slot = read(&vals[k * size..(k + 1) * size]);
        }
    }
    Ok(out)
}

/// An unsigned little-endian index of 1, 2 or 4 bytes.
fn index_at(b: &[u8]) -> u32 {
    match *b {
        [x] => u32::from(x),
        [x, y] => u32::from(u16::from_le_bytes([x, y])),
        [x, y, z, w] => u32::from_le_bytes([x, y, z, w]),
        _ => u32::MAX,
    }
}

/// A `POSITION` accessor: `VEC3` of `FLOAT`, every coordinate finite; at
/// most `max` vertices.
pub(super) fn positions(buffers: &[Vec<u8>], a: &gltf::Accessor<'_>, max: usize) -> Result<Vec<[f32; 3]>, Fault> {
    if (a.data_type(), a.dimensions(), a.normalized()) != (DataType::F32, Dimensions::Vec3, false) {
        let found =
            format!("{:?} of {:?}{}", a.dimensions(), a.data_type(), if a.normalized() { ", normalized" } else { "" });
        return Err(fault(a.index(), format!("POSITION must be Vec3 of F32; this is {found}")));
    }
    let f = |b: &[u8]| f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
    let points = elements(buffers, a, (12, max), |b| [f(&b[0..4]), f(&b[4..8]), f(&b[8..12])])?;
    if let Some(element) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err((format!("accessors[{}]", a.index()), GltfProblem::NonFinite { element }));
    }
    Ok(points)
}

/// An index accessor: `SCALAR` of unsigned bytes, shorts or ints; at
/// most `max` indices.
pub(super) fn indices(buffers: &[Vec<u8>], a: &gltf::Accessor<'_>, max: usize) -> Result<Vec<u32>, Fault> {
    let size = match (a.data_type(), a.dimensions()) {
        (DataType::U8, Dimensions::Scalar) => 1,
        (DataType::U16, Dimensions::Scalar) => 2,
        (DataType::U32, Dimensions::Scalar) => 4,
        (t, d) => {
            return Err(fault(
                a.index(),
                format!("indices must be a Scalar of U8, U16 or U32; this is {d:?} of {t:?}"),
            ));
        }
    };
    elements(buffers, a, (size, max), index_at)
}
