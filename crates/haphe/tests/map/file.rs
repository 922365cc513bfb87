//! Saving and loading: round trips, damaged files refused with the reason, crafted files
//! checked so that they never cause a panic.

use super::*;

/// A small solid and its map, encoded once.
pub(super) fn sample() -> &'static (Surface, VoxelMap, Vec<u8>) {
    static SAMPLE: OnceLock<(Surface, VoxelMap, Vec<u8>)> = OnceLock::new();
    SAMPLE.get_or_init(|| {
        let surface = surface(shapes::torus(0.07, 0.03, 16, 8));
        let map = build(&surface, &MapOptions::default());
        let bytes = encode(&surface, &map);
        (surface, map, bytes)
    })
}

/// Recomputes the checksum of a file (XXH3-64 of bytes 0..56 and of the XXH3-64 of each
/// 4 MiB chunk of bytes 64..).
fn reseal(bytes: &mut [u8]) {
    let mut hasher = xxhash_rust::xxh3::Xxh3::new();
    hasher.update(&bytes[..56]);
    for chunk in bytes[64..].chunks(4 << 20) {
        hasher.update(&xxhash_rust::xxh3::xxh3_64(chunk).to_le_bytes());
    }
    let sum = hasher.digest();
    bytes[56..64].copy_from_slice(&sum.to_le_bytes());
}

/// `value` written at byte `at` of a copy of the file `bytes`, the checksum recomputed:
/// the section named in the error.
fn refused_in(bytes: &[u8], at: usize, value: &[u8]) -> &'static str {
    let mut crafted = bytes.to_vec();
    crafted[at..at + value.len()].copy_from_slice(value);
    reseal(&mut crafted);
    match decode(&crafted) {
        Err(MapFileError::Invalid { section, .. }) => section,
        other => panic!("expected an invalid file, got {other:?}"),
    }
}

#[test]
fn loading_in_place_gives_the_same_surface_and_map_and_refuses_damage() {
    let (surface, map, bytes) = sample();
    let shared = MapBytes::read_from(&bytes[..]).expect("reads from a slice");
    let (surface2, map2) = decode_in_place(&shared).expect("loads in place");
    assert_eq!(&map2, map);
    assert_eq!(surface2.vertices(), surface.vertices());
    assert_eq!(surface2.triangles(), surface.triangles());
    assert_eq!(surface2.heap_bytes(), surface.heap_bytes());
    exercise(&surface2, &map2);
    // A flipped byte in the middle and a truncated file.
    let mut flipped = bytes.clone();
    let middle = flipped.len() / 2;
    flipped[middle] ^= 0x10;
    assert!(matches!(
        decode_in_place(&MapBytes::copy_from_slice(&flipped)),
        Err(MapFileError::ChecksumMismatch { .. })
    ));
    assert!(matches!(
        decode_in_place(&MapBytes::copy_from_slice(&bytes[..bytes.len() - 64])),
        Err(MapFileError::Truncated { .. })
    ));
    // A file of the previous format version is stale.
    let mut stale = bytes.clone();
    stale[8..12].copy_from_slice(&1u32.to_le_bytes());
    assert!(matches!(
        decode_in_place(&MapBytes::copy_from_slice(&stale)),
        Err(MapFileError::UnsupportedVersion { found: 1, .. })
    ));
}

/// Every accessor on every cell (and beyond), as a query would use a loaded map.
fn exercise(surface: &Surface, map: &VoxelMap) {
    let [dx, dy, dz] = map.grid().dims();
    for z in 0..=dz {
        for y in 0..=dy {
            for x in 0..=dx {
                let c = [x, y, z];
                let _ = (map.state(c), map.clearance(c));
                for &t in map.triangles_in(c) {
                    let _ = surface.corners(TriId(t));
                    let _ = surface.neighbours(TriId(t));
                }
            }
        }
    }
    for v in 0..surface.vertex_count() {
        for &t in surface.fan(haphe::mesh::VertId(v as u32)) {
            let _ = surface.frame(TriId(t));
        }
    }
    let _ = map.stats();
}

#[test]
fn encode_then_decode_gives_the_same_surface_and_map() {
    for (name, surface) in solids().into_iter().chain([("open", open_sphere())]) {
        let map = build(&surface, &MapOptions::default());
        let bytes = encode(&surface, &map);
        let (loaded_surface, loaded_map) = decode(&bytes).expect("decodes");
        assert_eq!(loaded_map, map, "{name}");
        assert_eq!(loaded_surface.vertices(), surface.vertices(), "{name}");
        assert_eq!(loaded_surface.triangles(), surface.triangles(), "{name}");
        assert_eq!(
            loaded_surface.source_triangles(),
            surface.source_triangles(),
            "{name}"
        );
        assert_eq!(loaded_surface.report(), surface.report(), "{name}");
        assert_eq!(loaded_surface.is_solid(), surface.is_solid(), "{name}");
        for t in 0..surface.triangle_count() {
            let t = TriId(t as u32);
            assert_eq!(loaded_surface.neighbours(t), surface.neighbours(t));
            assert_eq!(loaded_surface.frame(t), surface.frame(t));
            assert_eq!(loaded_surface.corner_normals(t), surface.corner_normals(t));
        }
        for v in 0..surface.vertex_count() {
            let v = haphe::mesh::VertId(v as u32);
            assert_eq!(loaded_surface.fan(v), surface.fan(v));
        }
        assert!(
            encode(&loaded_surface, &loaded_map) == bytes,
            "{name}: re-encoding differs"
        );
        // Any alignment of the buffer.
        let mut shifted = vec![0u8; 1];
        shifted.extend_from_slice(&bytes);
        assert_eq!(decode(&shifted[1..]).expect("decodes").1, map);
        assert_eq!(
            loaded_map.provenance(),
            None,
            "{name}: none recorded, none read"
        );

        // With the source recorded: read back exactly, and re-encoded to the same bytes.
        let source = Provenance::of(&format!("some/folder/{name} ✓.obj"), name.as_bytes());
        let map = map.with_provenance(source.clone());
        let bytes = encode(&surface, &map);
        let (loaded_surface, loaded_map) = decode(&bytes).expect("decodes");
        assert_eq!(loaded_map, map, "{name}");
        assert_eq!(loaded_map.provenance(), Some(&source), "{name}");
        assert_eq!(source.file, format!("{name} ✓.obj"));
        assert!(source.matches(name.as_bytes()) && !source.matches(b"other"));
        assert!(
            encode(&loaded_surface, &loaded_map) == bytes,
            "{name}: re-encoding differs"
        );
    }
}

/// A provenance record that this crate could not have written is refused, naming the
/// section; a long name is cut to the limit when recorded, and read back as cut.
#[test]
fn crafted_provenance_is_refused() {
    let (surface, map, _) = sample();
    let long = "é".repeat(MAX_SOURCE_NAME_BYTES);
    let source = Provenance::of(&long, b"x");
    assert!(
        source.file.len() <= MAX_SOURCE_NAME_BYTES
            && source.file.len() >= MAX_SOURCE_NAME_BYTES - 1
    );
    let map = map.clone().with_provenance(source.clone());
    assert_eq!(
        decode(&encode(surface, &map))
            .expect("decodes")
            .1
            .provenance(),
        Some(&source)
    );
    for bad in [
        Provenance {
            xxh3_128: "0123".into(),
            ..source.clone()
        },
        Provenance {
            xxh3_128: "G".repeat(32),
            ..source.clone()
        },
        Provenance {
            file: "x".repeat(MAX_SOURCE_NAME_BYTES + 1),
            ..source.clone()
        },
    ] {
        let bytes = encode(surface, &map.clone().with_provenance(bad.clone()));
        match decode(&bytes) {
            Err(MapFileError::Invalid { section, .. }) => {
                assert_eq!(section, "provenance", "{bad:?}")
            }
            other => panic!("{bad:?}: {other:?}"),
        }
    }
}

#[test]
fn damaged_files_are_refused_with_the_reason() {
    let (_, _, bytes) = sample();
    let mut wrong_magic = bytes.clone();
    wrong_magic[0] = b'X';
    assert!(matches!(
        decode(&wrong_magic),
        Err(MapFileError::WrongMagic { .. })
    ));

    let mut stale = bytes.clone();
    stale[8..12].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
    reseal(&mut stale);
    assert_eq!(
        decode(&stale).err(),
        Some(MapFileError::UnsupportedVersion {
            found: FORMAT_VERSION + 1,
            supported: FORMAT_VERSION
        })
    );

    for len in [0, 10, 63, 64, 200, bytes.len() / 2, bytes.len() - 1] {
        assert!(
            matches!(decode(&bytes[..len]), Err(MapFileError::Truncated { .. })),
            "{len} bytes"
        );
    }
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(matches!(
        decode(&longer),
        Err(MapFileError::TrailingBytes { .. })
    ));

    let mut flipped = bytes.clone();
    let middle = flipped.len() / 2;
    flipped[middle] ^= 0x10;
    assert!(matches!(
        decode(&flipped),
        Err(MapFileError::ChecksumMismatch { .. })
    ));

    let message = decode(&flipped).expect_err("damaged").to_string();
    assert!(message.contains("checksum"), "{message}");
}

#[test]
fn a_map_paired_with_another_surface_is_refused() {
    let (surface, _, _) = sample();
    let other = self::surface(shapes::sphere(0.1, 2));
    let map = build(&other, &MapOptions::default());
    let bytes = encode(surface, &map);
    match decode(&bytes) {
        Err(MapFileError::Invalid { section, .. }) => assert_eq!(section, "map parameters"),
        other => panic!("expected an invalid map, got {other:?}"),
    }
}

#[test]
fn crafted_files_with_a_valid_checksum_are_checked() {
    let (surface, _, bytes) = sample();
    let refused_in = |at: usize, value: &[u8]| refused_in(bytes, at, value);
    let sections = u32::from_le_bytes(bytes[12..16].try_into().expect("4 bytes")) as usize;
    // A triangle reference out of range, in the section before the slabs of the cells,
    // the bricks and the regions and the provenance (the last four).
    let last_ref = find_section_end(bytes, sections - 5) - 4;
    assert_eq!(
        refused_in(last_ref, &u32::MAX.to_le_bytes()),
        "triangle references"
    );
    // A triangle listed twice in one cell: the second entry of the first list of two or
    // more made a copy of its first.
    let (starts, refs) = (
        find_section_start(bytes, sections - 6),
        find_section_start(bytes, sections - 5),
    );
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    let first = (0..)
        .map(|s| (word(starts + 4 * s), word(starts + 4 * s + 4)))
        .find(|&(a, b)| b - a >= 2)
        .map(|(a, _)| refs + 4 * a as usize)
        .expect("a cell listing two triangles");
    assert_eq!(
        refused_in(first + 4, &word(first).to_le_bytes()),
        "triangle references"
    );
    // A vertex index out of range.
    let vertices = surface.vertex_count() as u32;
    let at = find_section_start(bytes, 2);
    assert_eq!(refused_in(at, &vertices.to_le_bytes()), "triangles");
    // A source triangle out of range.
    let triangles = surface.triangle_count() as u32;
    let at = find_section_start(bytes, 8);
    assert_eq!(refused_in(at, &triangles.to_le_bytes()), "source triangles");
    // A non-finite vertex.
    let at = find_section_start(bytes, 1);
    assert_eq!(refused_in(at, &f64::NAN.to_le_bytes()), "vertices");
}

/// Where section `k` starts, from the table (entry `k` at byte `64 + 32·k`).
fn find_section_start(bytes: &[u8], k: usize) -> usize {
    let at = 64 + 32 * k + 8;
    u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes")) as usize
}

fn find_section_end(bytes: &[u8], k: usize) -> usize {
    let at = 64 + 32 * k + 16;
    find_section_start(bytes, k)
        + u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes")) as usize
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Any damage is caught: flipped bytes anywhere always give an error, never a panic.
    #[test]
    fn flipped_bytes_are_always_refused(
        flips in prop::collection::vec((any::<prop::sample::Index>(), 1u8..=255), 1..5),
    ) {
        let (_, _, bytes) = sample();
        let mut damaged = bytes.clone();
        for (at, mask) in flips {
            damaged[at.index(bytes.len())] ^= mask;
        }
        prop_assert!(decode(&damaged).is_err());
    }

    /// Truncated or extended files are refused.
    #[test]
    fn truncated_or_extended_files_are_refused(cut in any::<prop::sample::Index>(), extra in prop::collection::vec(any::<u8>(), 1..100)) {
        let (_, _, bytes) = sample();
        prop_assert!(decode(&bytes[..cut.index(bytes.len())]).is_err());
        let mut longer = bytes.clone();
        longer.extend_from_slice(&extra);
        prop_assert!(decode(&longer).is_err());
    }

    /// A crafted file (bytes changed, checksum recomputed) either is refused or decodes to
    /// a surface and map that every accessor can use without a panic.
    #[test]
    fn crafted_files_never_cause_a_panic(
        changes in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..4),
        in_map in any::<bool>(),
    ) {
        let (_, _, bytes) = sample();
        let mut crafted = bytes.clone();
        // Half the cases aim at the map's sections (after the map parameters), which are
        // small next to the surface's.
        let start = if in_map { find_section_start(bytes, 9) } else { 0 };
        for (at, value) in changes {
            let i = start + at.index(bytes.len() - start);
            crafted[i] = value;
        }
        reseal(&mut crafted);
        if let Ok((surface, map)) = decode(&crafted) {
            exercise(&surface, &map);
        }
    }
}

/// The overlap cells of a saved map are checked: a brick index out of range, or a mask
/// reaching beyond the brick's inside cells, is refused naming its section.
#[test]
fn crafted_overlap_cells_are_refused() {
    let part = || shapes::cuboid(DVec3::splat(0.05), [5, 5, 5]);
    let (a, b) = (part(), part());
    let n = a.vertices.len() as u32;
    let mut mesh = a;
    mesh.vertices
        .extend(b.vertices.iter().map(|&v| v + DVec3::new(0.06, 0.03, 0.02)));
    mesh.triangles
        .extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
    let surface = surface(mesh);
    let map = build(&surface, &MapOptions::default());
    let bytes = encode(&surface, &map);
    let refused_in = |at: usize, value: &[u8]| refused_in(&bytes, at, value);
    // Sections 13 and 14: the overlap bricks and their masks.
    let (bricks, masks) = (
        find_section_start(&bytes, 13),
        find_section_start(&bytes, 14),
    );
    assert!(
        find_section_end(&bytes, 13) > bricks,
        "the two boxes overlap"
    );
    assert_eq!(
        refused_in(bricks, &u32::MAX.to_le_bytes()),
        "overlap bricks"
    );
    assert_eq!(refused_in(masks, &[0xff; 64]), "overlap masks");
    assert_eq!(decode(&bytes).expect("the file as written").1, map);
}
