//! Coordinates whose areas or volumes would overflow are refused when read and when a
//! surface is built, naming the vertex.

use haphe::DVec3;
use haphe::mesh::{
    MAX_COORDINATE, Mesh, Place, ReadErrorKind, ReadOptions, Surface, SurfaceOptions, Units,
    read_mesh,
};

#[test]
fn a_vertex_at_1e300_is_refused_at_read() {
    let obj = b"v 0 0 0\nv 1e300 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    let err = read_mesh("big.obj", obj, &ReadOptions::default()).unwrap_err();
    assert_eq!(
        err.kind,
        ReadErrorKind::CoordinateTooLarge {
            at: Place::Vertex(1),
            value: 1e300
        }
    );
    assert!(
        err.to_string()
            .starts_with("big.obj: vertex 1: a vertex coordinate of 1e300 m")
    );
}

/// The limit applies after scaling: 2e9 mm is 2e6 m (accepted), 2e9 m is not.
#[test]
fn the_limit_is_in_metres_after_scaling() {
    let obj = b"v 0 0 0\nv 2e9 0 0\nv 0 1 0\nf 1 2 3\n";
    let mm = ReadOptions {
        units: Units::Millimetres,
        ..ReadOptions::default()
    };
    assert!(read_mesh("mm.obj", obj, &mm).is_ok());
    assert!(read_mesh("m.obj", obj, &ReadOptions::default()).is_err());
}

#[test]
fn a_surface_is_not_built_from_such_a_mesh() {
    let mesh = Mesh {
        vertices: vec![
            DVec3::ZERO,
            DVec3::new(MAX_COORDINATE * 2.0, 0.0, 0.0),
            DVec3::Y,
        ],
        triangles: vec![[0, 1, 2]],
    };
    assert!(Surface::new(mesh, &SurfaceOptions::default()).is_err());
}
