//! Reeves' depth-map storage schemes (`sim::cost::storage`): the sparse tile store
//! reads back every texel of the dense map — rendered bundled scenes and
//! random maps — and the byte counts of the raw, bounding-box and tile
//! schemes match hand-computed values and a per-texel recount.

use std::collections::BTreeMap;

use proptest::prelude::*;
use umbra::core::{CullMode, DepthFormatKind, DepthUnit, LightPassConfig, NoProbe, RasterConfig};
use umbra::sim::cost::storage::{
    BOX_HEADER_BYTES, MapShape, REEVES_TILE, SparseTiles, StorageError, TILE_ENTRY_BYTES, TexelBox, finite_box,
    storage_bytes,
};
use umbra::sim::pass::light::RawMaps;
use umbra::sim::world::scene::Scene;

const CLEAR16: u32 = 0xffff;

fn shape16(width: u32, height: u32) -> MapShape {
    MapShape { width, height, texel_bytes: 2, clear: CLEAR16 }
}

/// Every texel, every tile's max, and reads outside the map.
fn assert_reads_back(shape: MapShape, dense: &[u32], tile: u32) -> Result<(), TestCaseError> {
    let s = SparseTiles::new(shape, dense, tile).expect("valid map");
    let w = shape.width;
    for y in 0..shape.height {
        for x in 0..w {
            prop_assert_eq!(s.get(x, y), Ok(dense[(y * w + x) as usize]), "texel ({}, {})", x, y);
        }
    }
    for ty in 0..shape.height.div_ceil(tile) {
        for tx in 0..w.div_ceil(tile) {
            let texels: Vec<u32> = (ty * tile..((ty + 1) * tile).min(shape.height))
                .flat_map(|y| (tx * tile..((tx + 1) * tile).min(w)).map(move |x| dense[(y * w + x) as usize]))
                .collect();
            let want = texels.iter().any(|&t| t != shape.clear).then(|| texels.iter().copied().max().unwrap());
            prop_assert_eq!(s.tile_max(tx, ty), want, "tile ({}, {})", tx, ty);
        }
    }
    let out = StorageError::OutOfMap { x: w, y: 0, width: w, height: shape.height };
    prop_assert_eq!(s.get(w, 0), Err(out));
    prop_assert!(s.get(0, shape.height).is_err());
    Ok(())
}

/// A 5×4 map of 16-bit texels, tiles of 2: tile (0, 0) full, one texel in
/// the bottom-right tile (2, 1), which the map's edge clips to 1×2.
///
/// ```text
///   x: 0   1   2   3   4
/// y0: 10  20   .   .   .
/// y1: 30 100   .   .   .
/// y2:  .   .   .   .   .
/// y3:  .   .   .   . 200
/// ```
#[test]
fn hand_made_map_byte_counts() {
    let shape = shape16(5, 4);
    let mut z1 = vec![CLEAR16; 20];
    for (x, y, v) in [(0, 0, 10), (1, 0, 20), (0, 1, 30), (1, 1, 100), (4, 3, 200)] {
        z1[y * 5 + x] = v;
    }
    let b = storage_bytes(&shape, &[&z1], 2).unwrap();
    // Raw: 5·4 texels · 2 bytes.
    assert_eq!(b.raw, 40);
    // Box: columns 0..5, rows 0..4 = 20 texels · 2 + the 8-byte header.
    assert_eq!(finite_box(&shape, &[&z1]).unwrap(), Some(TexelBox { x0: 0, y0: 0, x1: 5, y1: 4 }));
    assert_eq!(b.bounding_box, 48);
    // Tiles: 3×2 grid → 6 directory entries of 4 bytes = 24; tile (0, 0):
    // 4 texels · 2 + max 2 = 10; tile (2, 1): 2 texels · 2 + 2 = 6.
    assert_eq!((b.grid_tiles, b.stored_tiles), (6, 2));
    assert_eq!(b.tiles, 40);
    let s = SparseTiles::new(shape, &z1, 2).unwrap();
    assert_eq!(s.bytes(), 40);
    assert_eq!(s.tile_max(0, 0), Some(100));
    assert_eq!(s.tile_max(2, 1), Some(CLEAR16));
    assert_eq!(s.tile_max(1, 0), None);

    // A second buffer with one finite texel in tile (1, 0): the box grows
    // to nothing new, a third tile is stored, and every stored tile holds
    // both buffers.
    let mut z2 = vec![CLEAR16; 20];
    z2[2] = 300;
    let d = storage_bytes(&shape, &[&z1, &z2], 2).unwrap();
    assert_eq!(d.raw, 80);
    assert_eq!(d.bounding_box, 8 + 20 * 2 * 2);
    // 24 + (10 + 10 + 6) · 2.
    assert_eq!(d.tiles, 76);

    // Only the single texel at (4, 3): a 1×1 box.
    let mut lone = vec![CLEAR16; 20];
    lone[19] = 7;
    let l = storage_bytes(&shape, &[&lone], 2).unwrap();
    assert_eq!((l.bounding_box, l.tiles), (8 + 2, 24 + 6));

    // An empty map: the header and the directory only.
    let empty = vec![CLEAR16; 20];
    let e = storage_bytes(&shape, &[&empty], 2).unwrap();
    assert_eq!((e.raw, e.bounding_box, e.tiles, e.stored_tiles), (40, BOX_HEADER_BYTES, 6 * TILE_ENTRY_BYTES, 0));
    assert_eq!(finite_box(&shape, &[&empty]).unwrap(), None);
}

#[test]
fn bad_input_is_a_typed_error() {
    let z = vec![CLEAR16; 20];
    assert_eq!(storage_bytes(&shape16(5, 4), &[&z], 0), Err(StorageError::TileSize { size: 0 }));
    assert_eq!(storage_bytes(&shape16(0, 4), &[&z], 2), Err(StorageError::MapSize { width: 0, height: 4 }));
    let wide = MapShape { texel_bytes: 5, ..shape16(5, 4) };
    assert_eq!(storage_bytes(&wide, &[&z], 2), Err(StorageError::TexelBytes { bytes: 5 }));
    let short = vec![CLEAR16; 19];
    let err = storage_bytes(&shape16(5, 4), &[&z, &short], 2).unwrap_err();
    assert_eq!(err, StorageError::BufferLength { buffer: "z2".into(), expected: 20, found: 19 });
    assert!(SparseTiles::new(shape16(5, 4), &short, 2).is_err());
}

/// Render a bundled scene's dual 24-bit light maps at `size`².
fn scene_maps(name: &str, size: u32) -> umbra::sim::pass::light::RawMaps {
    let scene = Scene::bundled(name).expect("bundled scene");
    let raster = RasterConfig::new(size, size, 32, RasterConfig::DEFAULT_SUBPIXEL_BITS).unwrap();
    let cfg = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    let draws = scene.draws(scene.light().view_projection(), CullMode::None);
    RawMaps::render(cfg, DepthFormatKind::D24, &draws, NoProbe).expect("renders").0
}

#[test]
fn sparse_tiles_read_back_rendered_scenes() {
    for name in ["table-and-sphere", "crowd"] {
        let maps = scene_maps(name, 200);
        let shape = MapShape::of_format(200, 200, DepthFormatKind::D24);
        assert_eq!(shape.texel_bytes, 3);
        for tile in [REEVES_TILE, 24] {
            for (buffer, dense) in [("z1", &maps.maps.z1), ("z2", &maps.maps.z2)] {
                assert!(dense.iter().any(|&t| t != shape.clear), "{name} {buffer}: something rendered");
                assert_reads_back(shape, dense, tile).unwrap_or_else(|e| panic!("{name} {buffer} tile {tile}: {e}"));
                // One buffer alone: the tile scheme's count is the store's size.
                let one = storage_bytes(&shape, &[dense], tile).unwrap();
                assert_eq!(one.tiles, SparseTiles::new(shape, dense, tile).unwrap().bytes(), "{name} {buffer}");
            }
            // A dual pass keeps both buffers.
            assert_eq!(maps.buffers(), [&maps.maps.z1[..], &maps.maps.z2[..]]);
            let both = storage_bytes(&shape, &maps.buffers(), tile).unwrap();
            assert_eq!(both.raw, 200 * 200 * 3 * 2);
            assert_eq!(both.buffers, 2);
        }
    }
}

/// A sparse random map: clear, with rectangles of random depths.
fn sparse_map() -> impl Strategy<Value = (u32, u32, u32, Vec<u32>)> {
    (1u32..=48, 1u32..=48, 1u32..=20).prop_flat_map(|(w, h, tile)| {
        let rect = (0..w, 0..h, 1..=w, 1..=h, 0u32..CLEAR16);
        proptest::collection::vec(rect, 0..4).prop_map(move |rects| {
            let mut z = vec![CLEAR16; (w * h) as usize];
            for (x, y, rw, rh, v) in rects {
                for yy in y..(y + rh).min(h) {
                    for xx in x..(x + rw).min(w) {
                        // Vary the depth per texel so reads are position-checked.
                        z[(yy * w + xx) as usize] = (v + xx * 7 + yy * 13) % CLEAR16;
                    }
                }
            }
            (w, h, tile, z)
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Reads match the dense map, and the byte counts match a recount done
    /// texel by texel.
    #[test]
    fn random_maps((w, h, tile, z) in sparse_map()) {
        let shape = shape16(w, h);
        assert_reads_back(shape, &z, tile)?;
        // Recount: the box from the finite texels' extremes; the tiles from
        // the finite texels' tile indices, each tile's texels counted one by one.
        let finite: Vec<(u32, u32)> =
            (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).filter(|&(x, y)| z[(y * w + x) as usize] != CLEAR16).collect();
        let box_texels = match (finite.iter().map(|p| p.0).min(), finite.iter().map(|p| p.0).max()) {
            (Some(x0), Some(x1)) => {
                let (y0, y1) = (finite[0].1, finite[finite.len() - 1].1);
                u64::from(x1 - x0 + 1) * u64::from(y1 - y0 + 1)
            }
            _ => 0,
        };
        let occupied: std::collections::BTreeSet<(u32, u32)> = finite.iter().map(|&(x, y)| (x / tile, y / tile)).collect();
        let mut tile_texels: BTreeMap<(u32, u32), u64> = BTreeMap::new();
        for y in 0..h {
            for x in 0..w {
                *tile_texels.entry((x / tile, y / tile)).or_default() += 1;
            }
        }
        let stored: u64 = occupied.iter().map(|t| tile_texels[t] * 2 + 2).sum();
        let b = storage_bytes(&shape, &[&z], tile).unwrap();
        prop_assert_eq!(b.raw, u64::from(w * h) * 2);
        prop_assert_eq!(b.box_texels, box_texels);
        prop_assert_eq!(b.bounding_box, 8 + box_texels * 2);
        prop_assert_eq!(b.grid_tiles, tile_texels.len() as u64);
        prop_assert_eq!(b.stored_tiles, occupied.len() as u64);
        prop_assert_eq!(b.tiles, 4 * tile_texels.len() as u64 + stored);
        prop_assert!(b.bounding_box <= b.raw + 8);
    }
}
