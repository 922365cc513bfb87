//! Files refused: NIfTI-2, bad dimensions, data beyond the file, damaged gzip streams;
//! each before anything of the announced size is allocated.

use super::super::header::ByteOrder;
use super::{Kind, Spec, field_of, gzip, read_err, read_ok};

/// The most bytes a refused read may allocate at once: far below what the headers announce.
const SMALL_BYTES: u64 = 1 << 20;

/// `bytes` read and refused without allocating more than [`SMALL_BYTES`] at once.
fn refused_small(bytes: &[u8]) -> Kind {
    let mut kind = None;
    let info = allocation_counter::measure(|| kind = Some(read_err(bytes)));
    assert!(
        info.bytes_max < SMALL_BYTES,
        "{} bytes allocated",
        info.bytes_max
    );
    kind.expect("measured")
}

#[test]
fn nifti_2_is_refused_plainly_in_either_byte_order() {
    for order in [ByteOrder::Little, ByteOrder::Big] {
        let spec = Spec {
            order,
            sizeof_hdr: 540,
            ..Spec::default()
        };
        let e = crate::volume::Volume::read_nifti("brain.nii", &spec.file(&[0; 48]), 0.5)
            .expect_err("NIfTI-2");
        assert!(matches!(e, Kind::Nifti2 { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            "brain.nii: NIfTI-2 is not supported; convert to NIfTI-1 (sizeof_hdr is 540)"
        );
    }
}

#[test]
fn not_nifti_is_named() {
    assert!(matches!(read_err(b""), Kind::NotNifti { .. }));
    assert!(matches!(read_err(b"solid cube\n"), Kind::NotNifti { .. }));
    let pair = Spec {
        magic: *b"ni1\0",
        ..Spec::default()
    };
    let kind = read_err(&pair.file(&[0; 48]));
    assert!(kind.to_string().contains(".hdr/.img"), "{kind}");
    let wrong = Spec {
        magic: *b"abc\0",
        ..Spec::default()
    };
    assert!(
        read_err(&wrong.file(&[0; 48]))
            .to_string()
            .contains("\"abc\"")
    );
    // The header cut short.
    let spec = Spec::default();
    let kind = read_err(&spec.header()[..200]);
    assert_eq!(
        kind,
        Kind::Truncated {
            file: "t.nii".to_owned(),
            what: "file",
            needed: 348,
            available: 200
        }
    );
}

#[test]
fn dim_0_outside_1_to_7_is_refused_in_either_byte_order() {
    for order in [ByteOrder::Little, ByteOrder::Big] {
        for dim0 in [0, 8, -1] {
            let spec = Spec {
                order,
                dim: [dim0, 2, 3, 4, 1, 1, 1, 1],
                ..Spec::default()
            };
            let kind = read_err(&spec.file(&spec.int16(0..24)));
            assert_eq!(field_of(&kind), "dim[0]", "{order:?} {dim0}");
            assert!(
                kind.to_string().contains(&format!("dim[0]: {dim0}:")),
                "{kind}"
            );
        }
    }
}

#[test]
fn spatial_dims_below_1_are_refused() {
    for (dim, field) in [
        ([3, 2, 0, 4], "dim[2]"),
        ([3, 2, 3, -4], "dim[3]"),
        ([1, 0, 9, 9], "dim[1]"),
    ] {
        let spec = Spec {
            dim: [dim[0], dim[1], dim[2], dim[3], 1, 1, 1, 1],
            ..Spec::default()
        };
        assert_eq!(field_of(&read_err(&spec.file(&[0; 48]))), field);
    }
    let spec = Spec {
        dim: [4, 2, 3, 4, 0, 1, 1, 1],
        ..Spec::default()
    };
    assert_eq!(field_of(&read_err(&spec.file(&[0; 48]))), "dim[4]");
}

#[test]
fn absurd_dims_are_refused_without_allocating() {
    // NIfTI-1 dims are 16-bit: 32767³ voxels is the most a header can announce, far beyond
    // MAX_VOXELS. The file is the header alone, plain and compressed.
    let spec = Spec {
        dim: [3, i16::MAX, i16::MAX, i16::MAX, 1, 1, 1, 1],
        ..Spec::default()
    };
    let kind = refused_small(&spec.file(&[]));
    assert_eq!(field_of(&kind), "dim[1..3]");
    assert!(kind.to_string().contains("32767 × 32767 × 32767"), "{kind}");
    assert_eq!(
        field_of(&refused_small(&gzip(&spec.file(&[])))),
        "dim[1..3]"
    );
    // Within MAX_VOXELS (2^30 voxels, 2 GiB of int16) but beyond the file.
    let big = Spec {
        dim: [3, 1 << 14, 1 << 14, 4, 1, 1, 1, 1],
        ..Spec::default()
    };
    let kind = refused_small(&big.file(&[0; 100]));
    assert_eq!(
        kind,
        Kind::Truncated {
            file: "t.nii".to_owned(),
            what: "file",
            needed: 352 + (1 << 31),
            available: 452
        }
    );
}

#[test]
fn truncated_data_and_a_far_vox_offset_are_refused() {
    let spec = Spec::default();
    let mut file = spec.file(&spec.int16(0..24));
    file.pop();
    let kind = read_err(&file);
    assert_eq!(
        kind,
        Kind::Truncated {
            file: "t.nii".to_owned(),
            what: "file",
            needed: 400,
            available: 399
        }
    );
    assert_eq!(
        kind.to_string(),
        "t.nii: the file ends early: 399 bytes of the 400 its header announces"
    );
    let far = Spec {
        vox_offset: 1000.0,
        ..Spec::default()
    };
    let mut file = far.header();
    file.extend_from_slice(&far.int16(0..24));
    let kind = read_err(&file);
    assert!(
        matches!(
            kind,
            Kind::Truncated {
                needed: 1048,
                available: 400,
                ..
            }
        ),
        "{kind}"
    );
    let huge = Spec {
        vox_offset: 1e30,
        ..Spec::default()
    };
    let kind = read_err(&huge.header());
    assert!(
        matches!(
            kind,
            Kind::Truncated {
                needed: u64::MAX,
                ..
            }
        ),
        "{kind}"
    );
    for vox_offset in [0.0, 348.0, f32::NAN, -1.0] {
        let low = Spec {
            vox_offset,
            ..Spec::default()
        };
        assert_eq!(
            field_of(&read_err(&low.file(&low.int16(0..24)))),
            "vox_offset"
        );
    }
    // A larger offset (extensions before the data) is read.
    let ext = Spec {
        vox_offset: 400.0,
        ..Spec::default()
    };
    assert_eq!(read_ok(&ext.file(&ext.int16(0..24))).0.values()[23], 23.0);
}

#[test]
fn a_truncated_gzip_stream_is_an_error() {
    let spec = Spec {
        dim: [3, 20, 20, 20, 1, 1, 1, 1],
        ..Spec::default()
    };
    let data: Vec<u8> = (0..8000)
        .flat_map(|i: i32| spec.int16([(i * 7919 % 32000) as i16]))
        .collect();
    let whole = gzip(&spec.file(&data));
    assert!(read_ok(&whole).0.values().len() == 8000);
    for cut in [whole.len() / 2, 20, whole.len() - 12] {
        let kind = read_err(&whole[..cut]);
        assert!(
            matches!(kind, Kind::Gzip { .. } | Kind::Truncated { .. }),
            "cut at {cut}: {kind}"
        );
    }
}

#[test]
fn a_gzip_bomb_is_refused_before_it_is_decompressed() {
    // 1024 × 1024 × 512 uint8 (512 MiB) announced by a stream of a few hundred bytes.
    let spec = Spec {
        dim: [3, 1024, 1024, 512, 1, 1, 1, 1],
        datatype: 2,
        ..Spec::default()
    };
    let kind = refused_small(&gzip(&spec.file(&[0; 4096])));
    assert_eq!(field_of(&kind), "dim");
    assert!(
        kind.to_string().contains("compressed bytes can hold"),
        "{kind}"
    );
    // A stream that goes on long past the data: only what the header needs is read.
    let small = Spec::default();
    let mut file = small.file(&small.int16(0..24));
    file.resize(64 << 20, 0);
    let bomb = gzip(&file);
    let mut read = None;
    let info = allocation_counter::measure(|| read = Some(read_ok(&bomb)));
    assert!(
        info.bytes_max < SMALL_BYTES * 4,
        "{} bytes allocated",
        info.bytes_max
    );
    assert_eq!(read.expect("measured").0.values()[23], 23.0);
}

#[test]
fn mutated_files_give_a_volume_or_an_error() {
    // A few bytes changed at random, mostly in the header, plain and compressed: never a
    // panic (the fuzz target does this at length).
    let spec = Spec {
        qform_code: 1,
        ..Spec::default()
    };
    let plain = spec.file(&spec.int16(0..24));
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for _ in 0..3000 {
        let mut bytes = plain.clone();
        for _ in 0..1 + next() % 4 {
            let at = (next() % 352) as usize;
            bytes[at] = next() as u8;
        }
        let _ = crate::volume::Volume::read_nifti("m.nii", &bytes, 0.5);
        let _ = crate::volume::Volume::read_nifti("m.nii.gz", &gzip(&bytes), 0.5);
    }
}
