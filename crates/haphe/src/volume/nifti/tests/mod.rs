//! NIfTI-1 files written byte by byte here (either byte order, every datatype), read back;
//! the expected affines worked out by hand from the standard and nibabel's rules.

mod affine;
mod limits;
mod round_trip;

use std::io::Write;

use flate2::write::GzEncoder;

use super::ReadVolumeError as Kind;
use super::header::ByteOrder;
use crate::volume::{Volume, VolumeError};

/// The header fields the tests set; the rest are zero.
#[derive(Debug, Clone)]
pub(super) struct Spec {
    pub order: ByteOrder,
    pub sizeof_hdr: i32,
    pub dim: [i16; 8],
    pub datatype: i16,
    pub pixdim: [f32; 8],
    pub vox_offset: f32,
    pub scl: [f32; 2],
    pub xyzt_units: u8,
    pub qform_code: i16,
    pub sform_code: i16,
    /// quatern_b, c, d, qoffset_x, y, z.
    pub quatern: [f32; 6],
    pub srow: [[f32; 4]; 3],
    pub magic: [u8; 4],
}

impl Default for Spec {
    /// 2 × 3 × 4 int16, little-endian, 1 mm voxels, no sform or qform.
    fn default() -> Spec {
        Spec {
            order: ByteOrder::Little,
            sizeof_hdr: 348,
            dim: [3, 2, 3, 4, 1, 1, 1, 1],
            datatype: 4,
            pixdim: [1.0; 8],
            vox_offset: 352.0,
            scl: [0.0, 0.0],
            xyzt_units: 2,
            qform_code: 0,
            sform_code: 0,
            quatern: [0.0; 6],
            srow: [[0.0; 4]; 3],
            magic: *b"n+1\0",
        }
    }
}

impl Spec {
    /// The 352 bytes of the header and the extension flag.
    pub fn header(&self) -> Vec<u8> {
        let mut h = vec![0u8; 352];
        let mut put = |at: usize, le: &[u8]| {
            let mut b = le.to_vec();
            if self.order == ByteOrder::Big {
                b.reverse();
            }
            h[at..at + b.len()].copy_from_slice(&b);
        };
        put(0, &self.sizeof_hdr.to_le_bytes());
        for (i, d) in self.dim.iter().enumerate() {
            put(40 + 2 * i, &d.to_le_bytes());
        }
        put(70, &self.datatype.to_le_bytes());
        for (i, p) in self.pixdim.iter().enumerate() {
            put(76 + 4 * i, &p.to_le_bytes());
        }
        put(108, &self.vox_offset.to_le_bytes());
        put(112, &self.scl[0].to_le_bytes());
        put(116, &self.scl[1].to_le_bytes());
        put(123, &[self.xyzt_units]);
        put(252, &self.qform_code.to_le_bytes());
        put(254, &self.sform_code.to_le_bytes());
        for (i, q) in self.quatern.iter().enumerate() {
            put(256 + 4 * i, &q.to_le_bytes());
        }
        for (r, row) in self.srow.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                put(280 + 16 * r + 4 * j, &v.to_le_bytes());
            }
        }
        h[344..348].copy_from_slice(&self.magic);
        h
    }

    /// The file: the header, zeros up to `vox_offset`, then `data`.
    pub fn file(&self, data: &[u8]) -> Vec<u8> {
        let mut f = self.header();
        f.resize((self.vox_offset as usize).max(352), 0);
        f.extend_from_slice(data);
        f
    }

    /// `values` encoded as int16 in the spec's byte order.
    pub fn int16(&self, values: impl IntoIterator<Item = i16>) -> Vec<u8> {
        values
            .into_iter()
            .flat_map(|v| self.ordered(&v.to_le_bytes()))
            .collect()
    }

    /// Little-endian bytes in the spec's byte order.
    pub fn ordered(&self, le: &[u8]) -> Vec<u8> {
        let mut b = le.to_vec();
        if self.order == ByteOrder::Big {
            b.reverse();
        }
        b
    }
}

/// `bytes` as a gzip stream.
pub(super) fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut e = GzEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(bytes).expect("a Vec takes every byte");
    e.finish().expect("a Vec takes every byte")
}

/// Reads `bytes` with iso 0.5, expecting success.
pub(super) fn read_ok(bytes: &[u8]) -> (Volume, super::NiftiInfo) {
    Volume::read_nifti("t.nii", bytes, 0.5).unwrap_or_else(|e| panic!("{e}"))
}

/// Reads `bytes`, expecting an error; its kind.
pub(super) fn read_err(bytes: &[u8]) -> Kind {
    let e = Volume::read_nifti("t.nii", bytes, 0.5).expect_err("refused");
    assert!(e.to_string().starts_with("t.nii: "), "{e}");
    e
}

/// The field of a header error.
pub(super) fn field_of(kind: &Kind) -> &'static str {
    match kind {
        Kind::Header { field, .. } => field,
        other => panic!("not a header error: {other}"),
    }
}

#[test]
fn little_endian_int16_is_read_i_fastest() {
    let spec = Spec::default();
    let (v, info) = read_ok(&spec.file(&spec.int16(0..24)));
    assert_eq!(v.dims(), [2, 3, 4]);
    assert_eq!(
        v.values(),
        &(0..24).map(|x| x as f32).collect::<Vec<_>>()[..]
    );
    assert_eq!(v.value(1, 2, 3), 23.0);
    assert_eq!(v.value(1, 0, 1), 7.0);
    assert_eq!(info.datatype, "int16");
    assert_eq!(info.byte_order, "little-endian");
    assert!(!info.gzip);
    assert_eq!(info.value_range, (0.0, 23.0));
    assert_eq!(info.metres_per_unit, 1e-3);
    assert!(info.notes.is_empty(), "{:?}", info.notes);
}

#[test]
fn big_endian_reads_the_same_volume() {
    let little = Spec::default();
    let big = Spec {
        order: ByteOrder::Big,
        ..Spec::default()
    };
    let a = read_ok(&little.file(&little.int16(-12..12)));
    let b = read_ok(&big.file(&big.int16(-12..12)));
    assert_eq!(a.0, b.0);
    assert_eq!(b.1.byte_order, "big-endian");
    assert_eq!(b.1.value_range, (-12.0, 11.0));
}

#[test]
fn gzip_is_detected_by_its_magic_not_the_name() {
    for order in [ByteOrder::Little, ByteOrder::Big] {
        let spec = Spec {
            order,
            ..Spec::default()
        };
        let plain = spec.file(&spec.int16(0..24));
        let (v, info) = read_ok(&gzip(&plain));
        assert_eq!(v, read_ok(&plain).0);
        assert!(info.gzip);
        assert_eq!(info.byte_order, order.name());
    }
}

/// Each datatype read: its code, nibabel's name and the little-endian bytes of 0, 1, 2
/// and its largest value, with that value as an `f32`.
type Case = (i16, &'static str, Vec<u8>, f32);

fn every_datatype() -> Vec<Case> {
    fn case<const N: usize>(code: i16, name: &'static str, v: [[u8; N]; 4], top: f32) -> Case {
        (code, name, v.concat(), top)
    }
    vec![
        case(2, "uint8", [0u8, 1, 2, u8::MAX].map(u8::to_le_bytes), 255.0),
        case(
            256,
            "int8",
            [0i8, 1, 2, i8::MIN].map(i8::to_le_bytes),
            -128.0,
        ),
        case(
            512,
            "uint16",
            [0u16, 1, 2, u16::MAX].map(u16::to_le_bytes),
            65535.0,
        ),
        case(
            4,
            "int16",
            [0i16, 1, 2, i16::MIN].map(i16::to_le_bytes),
            -32768.0,
        ),
        case(
            768,
            "uint32",
            [0u32, 1, 2, u32::MAX].map(u32::to_le_bytes),
            4294967296.0,
        ),
        case(
            8,
            "int32",
            [0i32, 1, 2, i32::MIN].map(i32::to_le_bytes),
            -2147483648.0,
        ),
        case(
            1280,
            "uint64",
            [0u64, 1, 2, 1 << 40].map(u64::to_le_bytes),
            1099511627776.0,
        ),
        case(
            1024,
            "int64",
            [0i64, 1, 2, -(1 << 40)].map(i64::to_le_bytes),
            -1099511627776.0,
        ),
        case(
            16,
            "float32",
            [0f32, 1.0, 2.0, -0.25].map(f32::to_le_bytes),
            -0.25,
        ),
        case(
            64,
            "float64",
            [0f64, 1.0, 2.0, 1e300].map(f64::to_le_bytes),
            f32::INFINITY,
        ),
    ]
}

#[test]
fn every_datatype_in_both_byte_orders() {
    for (code, name, le, top) in every_datatype() {
        for order in [ByteOrder::Little, ByteOrder::Big] {
            let spec = Spec {
                order,
                datatype: code,
                dim: [3, 4, 1, 1, 1, 1, 1, 1],
                ..Spec::default()
            };
            let size = le.len() / 4;
            let data: Vec<u8> = le.chunks(size).flat_map(|b| spec.ordered(b)).collect();
            let (v, info) = read_ok(&spec.file(&data));
            assert_eq!(v.values(), &[0.0, 1.0, 2.0, top], "{name} {order:?}");
            assert_eq!(info.datatype, name);
        }
    }
}

#[test]
fn other_datatypes_are_refused_by_name() {
    for (code, words) in [
        (32, "complex64"),
        (128, "RGB24"),
        (1, "binary"),
        (99, "not a NIfTI-1 datatype"),
    ] {
        let spec = Spec {
            datatype: code,
            ..Spec::default()
        };
        let kind = read_err(&spec.file(&[0; 400]));
        assert_eq!(field_of(&kind), "datatype");
        assert!(kind.to_string().contains(words), "{kind}");
    }
}

#[test]
fn scl_slope_and_inter_apply_when_the_slope_is_finite_and_not_zero() {
    let values = |scl: [f32; 2]| {
        let spec = Spec {
            scl,
            ..Spec::default()
        };
        Volume::read_nifti("s.nii", &spec.file(&spec.int16(0..24)), 0.0)
            .map(|r| r.0.values()[..3].to_vec())
    };
    assert_eq!(values([2.0, -1.0]), Ok(vec![-1.0, 1.0, 3.0]));
    assert_eq!(values([0.5, 0.0]), Ok(vec![0.0, 0.5, 1.0]));
    assert_eq!(values([0.0, 7.0]), Ok(vec![0.0, 1.0, 2.0]));
    assert_eq!(values([f32::NAN, 7.0]), Ok(vec![0.0, 1.0, 2.0]));
    assert_eq!(values([f32::INFINITY, 7.0]), Ok(vec![0.0, 1.0, 2.0]));
    let e = values([2.0, f32::NAN]).expect_err("a NaN intercept");
    assert!(
        matches!(
            e,
            Kind::Header {
                field: "scl_inter",
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn a_four_d_file_gives_its_first_volume_with_a_note() {
    let spec = Spec {
        dim: [4, 2, 3, 4, 12, 1, 1, 1],
        ..Spec::default()
    };
    let (v, info) = read_ok(&spec.file(&spec.int16((0..24 * 12).map(|x| x as i16))));
    assert_eq!(v.dims(), [2, 3, 4]);
    assert_eq!(info.value_range, (0.0, 23.0));
    assert_eq!(info.notes, ["4-D file: the first of 12 volumes is used"]);
    // Five dimensions: the volumes multiply.
    let spec = Spec {
        dim: [5, 2, 3, 4, 2, 3, 1, 1],
        ..Spec::default()
    };
    let info = read_ok(&spec.file(&spec.int16(0..24))).1;
    assert_eq!(info.notes, ["5-D file: the first of 6 volumes is used"]);
}

#[test]
fn a_nan_voxel_is_named() {
    let spec = Spec {
        datatype: 16,
        ..Spec::default()
    };
    let mut values = [0f32; 24];
    values[1 + 2 * (2 + 3 * 3)] = f32::NAN;
    let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let kind = read_err(&spec.file(&data));
    assert!(
        matches!(
            kind,
            Kind::Volume {
                error: VolumeError::NotANumber([1, 2, 3]),
                ..
            }
        ),
        "{kind}"
    );
    assert_eq!(kind.to_string(), "t.nii: voxel [1, 2, 3] is NaN");
}
