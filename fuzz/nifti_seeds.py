#!/usr/bin/env python3
"""Writes seed files for the `read_nifti` fuzz target into the folder given (default
corpus/read_nifti), written by nibabel, the reference reader: a little-endian int16 volume
placed by an sform, a big-endian float32 `.nii.gz` placed by a qform only, a 4-D uint8
volume in metres, and a float64 volume with scl_slope and scl_inter. Needs numpy and
nibabel."""

import sys
from pathlib import Path

import nibabel as nib
import numpy as np


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "corpus/read_nifti")
    out.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(1)

    labels = np.zeros((4, 5, 3), dtype=np.int16)
    labels[1:3, 1:4, 1] = 7
    nib.Nifti1Image(labels, np.diag([0.5, 0.5, 0.7, 1.0])).to_filename(out / "sform.nii")

    scan = nib.Nifti1Image(rng.random((3, 3, 3)).astype(">f4"), None)
    scan.set_qform(np.diag([1.0, 2.0, 3.0, 1.0]), code=1)
    scan.set_sform(None, code=0)
    scan.to_filename(out / "qform-big-endian.nii.gz")

    series = nib.Nifti1Image((rng.random((2, 3, 4, 2)) * 100).astype(np.uint8), np.eye(4))
    series.header.set_xyzt_units("meter")
    series.to_filename(out / "four-d-metres.nii")

    scaled = nib.Nifti1Image(rng.random((3, 2, 2)), np.eye(4))
    scaled.header["scl_slope"] = 2.0
    scaled.header["scl_inter"] = 1.0
    scaled.to_filename(out / "scaled.nii")
    print(f"4 seeds written to {out}")


if __name__ == "__main__":
    main()
