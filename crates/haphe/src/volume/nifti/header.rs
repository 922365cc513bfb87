//! The header of a NIfTI-1 file, checked before any data is read or allocated: the byte
//! order (from `sizeof_hdr`), the magic, the dimensions, the datatype and where the data
//! start. The 348 bytes are parsed by the `nifti` crate once the checks made on the raw
//! bytes (which it does not make, or makes with a less precise error) have passed.

use nifti::{Endianness, NiftiHeader};

use super::error::{ReadVolumeError as Kind, header_error, not_nifti, truncated};
use crate::volume::MAX_VOXELS;

/// The bytes of a NIfTI-1 header.
pub(super) const HEADER_BYTES: usize = 348;
/// `sizeof_hdr` of a NIfTI-2 header.
const NIFTI2_HEADER_BYTES: i32 = 540;
/// Where the data of a single-file NIfTI-1 may start at the earliest: after the header and
/// the four bytes of the extension flag.
pub(super) const FIRST_DATA_BYTE: u64 = 352;

const DIM_FIELDS: [&str; 8] = [
    "dim[0]", "dim[1]", "dim[2]", "dim[3]", "dim[4]", "dim[5]", "dim[6]", "dim[7]",
];

/// The byte order of a file's numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum ByteOrder {
    /// Least significant byte first (x86, ARM: most files).
    Little,
    /// Most significant byte first.
    Big,
}

impl ByteOrder {
    /// How reports name it.
    pub fn name(self) -> &'static str {
        match self {
            ByteOrder::Little => "little-endian",
            ByteOrder::Big => "big-endian",
        }
    }
}

/// A voxel type: the NIfTI code, nibabel's name for it and its size in bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Datatype {
    pub code: i16,
    pub name: &'static str,
    pub bytes: usize,
}

/// The datatypes read, by code.
const READ: [Datatype; 10] = [
    Datatype {
        code: 2,
        name: "uint8",
        bytes: 1,
    },
    Datatype {
        code: 4,
        name: "int16",
        bytes: 2,
    },
    Datatype {
        code: 8,
        name: "int32",
        bytes: 4,
    },
    Datatype {
        code: 16,
        name: "float32",
        bytes: 4,
    },
    Datatype {
        code: 64,
        name: "float64",
        bytes: 8,
    },
    Datatype {
        code: 256,
        name: "int8",
        bytes: 1,
    },
    Datatype {
        code: 512,
        name: "uint16",
        bytes: 2,
    },
    Datatype {
        code: 768,
        name: "uint32",
        bytes: 4,
    },
    Datatype {
        code: 1024,
        name: "int64",
        bytes: 8,
    },
    Datatype {
        code: 1280,
        name: "uint64",
        bytes: 8,
    },
];

/// The datatypes of the standard that are refused, by code.
const REFUSED: [(i16, &str); 7] = [
    (1, "binary (1 bit per voxel)"),
    (32, "complex64"),
    (128, "RGB24"),
    (1536, "float128"),
    (1792, "complex128"),
    (2048, "complex256"),
    (2304, "RGBA32"),
];

/// A checked header: what the data are and where they are.
#[derive(Debug, Clone)]
pub(super) struct Layout {
    /// The parsed header.
    pub header: NiftiHeader,
    pub order: ByteOrder,
    /// Voxels along i, j, k (1 beyond `dim[0]`).
    pub dims: [usize; 3],
    /// How many 3-D volumes the file holds (the product of `dim[4..=dim[0]]`).
    pub volumes: u64,
    pub datatype: Datatype,
    /// The byte where the data start.
    pub offset: u64,
}

impl Layout {
    /// The bytes of the first volume's data.
    pub fn volume_bytes(&self) -> u64 {
        self.dims.iter().map(|&d| d as u64).product::<u64>() * self.datatype.bytes as u64
    }

    /// The byte after the first volume's data: how much of the file is needed.
    pub fn end(&self) -> u64 {
        // A huge vox_offset saturates: no file is that long, so it is refused as truncated.
        self.offset.saturating_add(self.volume_bytes())
    }
}

/// Checks the 348 bytes of a header (the start of the file, decompressed) and says where
/// the data are.
///
/// # Errors
/// NIfTI-2, a wrong `sizeof_hdr` or magic, a short header, and a bad `dim`, `datatype` or
/// `vox_offset`.
pub(super) fn layout(head: &[u8]) -> Result<Layout, Kind> {
    let order = byte_order(head)?;
    if head.len() < HEADER_BYTES {
        return Err(truncated("file", HEADER_BYTES as u64, head.len() as u64));
    }
    check_magic(&head[344..HEADER_BYTES])?;
    let dim0 = i16_at(head, 40, order);
    if !(1..=7).contains(&dim0) {
        return Err(header_error(
            "dim[0]",
            format!("{dim0}: the number of dimensions must be 1 to 7"),
        ));
    }
    let header =
        NiftiHeader::from_reader(&head[..HEADER_BYTES]).map_err(|e| not_nifti(e.to_string()))?;
    let parsed = match header.endianness {
        Endianness::Little => ByteOrder::Little,
        Endianness::Big => ByteOrder::Big,
    };
    if parsed != order {
        return Err(not_nifti(
            "the byte orders of sizeof_hdr and dim[0] differ".to_owned(),
        ));
    }
    let (dims, volumes) = dims(&header)?;
    Ok(Layout {
        datatype: datatype(header.datatype)?,
        offset: data_offset(header.vox_offset)?,
        header,
        order,
        dims,
        volumes,
    })
}

/// The byte order whose `sizeof_hdr` is 348.
fn byte_order(head: &[u8]) -> Result<ByteOrder, Kind> {
    let Some(first) = head.first_chunk::<4>() else {
        return Err(not_nifti(format!(
            "{} bytes, too short for a header",
            head.len()
        )));
    };
    let (little, big) = (i32::from_le_bytes(*first), i32::from_be_bytes(*first));
    if little == HEADER_BYTES as i32 {
        Ok(ByteOrder::Little)
    } else if big == HEADER_BYTES as i32 {
        Ok(ByteOrder::Big)
    } else if little == NIFTI2_HEADER_BYTES || big == NIFTI2_HEADER_BYTES {
        Err(Kind::Nifti2 {
            file: String::new(),
        })
    } else {
        Err(not_nifti(format!(
            "sizeof_hdr is {little} (little-endian) or {big} (big-endian), not 348"
        )))
    }
}

/// The magic of a single-file NIfTI-1 (`n+1\0`).
fn check_magic(magic: &[u8]) -> Result<(), Kind> {
    match magic {
        b"n+1\0" => Ok(()),
        b"ni1\0" => Err(not_nifti(
            "magic \"ni1\": the header of a .hdr/.img pair; only single-file .nii is \
                     read (convert the pair to .nii)"
                .to_owned(),
        )),
        _ => Err(not_nifti(format!(
            "magic is {:?}, not \"n+1\"",
            String::from_utf8_lossy(magic).trim_end_matches('\0')
        ))),
    }
}

/// The spatial dimensions (1 beyond `dim[0]`) and the number of volumes.
fn dims(header: &NiftiHeader) -> Result<([usize; 3], u64), Kind> {
    let dim0 = usize::from(header.dim[0]);
    // The standard's dims are signed 16-bit numbers; the crate reads them unsigned.
    let dim = |i: usize| header.dim[i] as i16;
    let mut spatial = [1usize; 3];
    for (i, side) in spatial.iter_mut().enumerate().take(dim0) {
        let d = dim(i + 1);
        if d < 1 {
            return Err(header_error(
                DIM_FIELDS[i + 1],
                format!("{d}: a spatial dimension must be at least 1"),
            ));
        }
        *side = d as usize;
    }
    let mut volumes = 1u64;
    for (i, field) in DIM_FIELDS.iter().enumerate().take(dim0 + 1).skip(4) {
        let d = dim(i);
        if d < 1 {
            return Err(header_error(
                field,
                format!("{d}: the file holds no volume"),
            ));
        }
        volumes *= d as u64;
    }
    let count = spatial.iter().map(|&d| d as u64).product::<u64>();
    if count > MAX_VOXELS as u64 {
        let [nx, ny, nz] = spatial;
        return Err(header_error(
            "dim[1..3]",
            format!("{nx} × {ny} × {nz} = {count} voxels, more than {MAX_VOXELS}"),
        ));
    }
    Ok((spatial, volumes))
}

/// The datatype of `code`, if it is one that is read.
fn datatype(code: i16) -> Result<Datatype, Kind> {
    if let Some(known) = READ.iter().find(|d| d.code == code) {
        return Ok(*known);
    }
    let message = match REFUSED.iter().find(|(c, _)| *c == code) {
        Some((_, name)) => format!(
            "{code} ({name}) is not supported: haphe reads integer and float32/float64 scalars"
        ),
        None => format!("{code} is not a NIfTI-1 datatype"),
    };
    Err(header_error("datatype", message))
}

/// The byte where the data start (`vox_offset`, a float in the header).
fn data_offset(vox_offset: f32) -> Result<u64, Kind> {
    if !vox_offset.is_finite() || vox_offset < FIRST_DATA_BYTE as f32 {
        return Err(header_error(
            "vox_offset",
            format!("{vox_offset}: a single-file NIfTI-1's data start at byte 352 or later"),
        ));
    }
    // nibabel truncates a fractional offset the same way.
    Ok(vox_offset as u64)
}

/// The 16-bit integer at `at` in `order`.
pub(super) fn i16_at(head: &[u8], at: usize, order: ByteOrder) -> i16 {
    let b = [head[at], head[at + 1]];
    match order {
        ByteOrder::Little => i16::from_le_bytes(b),
        ByteOrder::Big => i16::from_be_bytes(b),
    }
}
