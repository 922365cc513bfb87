//! A shape's texture coordinates: `[u, v]` at each corner of each surface triangle, and
//! the texture coordinate (with its gradients) at a point of a triangle.
//!
//! They come per triangle of the mesh as it was loaded; the surface stores its triangles in
//! its own order ([`Surface::source_triangle`]), so they are put into that order here, each
//! corner's coordinate going to the surface corner at the same place (a triangle whose
//! winding was turned over has its corners permuted).

use glam::{DVec2, DVec3};

use crate::mesh::{DEGENERATE_MAX_RELATIVE_HEIGHT, Surface, TriFrame, TriId};

/// The texture coordinate at a point of a triangle, and how it changes along the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct UvPoint {
    /// `[u, v]` at the point (`v` pointing up the image).
    pub uv: DVec2,
    /// The gradient of `u` over the triangle's plane, 1/metres, object frame: for a
    /// displacement `δ` in the plane, `u` changes by `grad_u · δ`. It lies in the plane.
    pub grad_u: DVec3,
    /// The gradient of `v`, likewise.
    pub grad_v: DVec3,
}

/// The texture coordinates of every surface triangle's corners, in the surface's order:
/// `per_loaded[surface.source_triangle(t)]` for triangle `t`, its corners matched to `t`'s
/// by place when `loaded_corners` gives the loaded triangles' corner positions (the
/// permutation of the three that puts them nearest), else taken in the same order (the
/// surface keeps the loaded corners' order).
///
/// The caller checked that `per_loaded` (and `loaded_corners`) has one entry per triangle
/// of the surface; a triangle whose source is out of range gets zeros.
pub(super) fn in_surface_order(
    surface: &Surface,
    per_loaded: &[[[f64; 2]; 3]],
    loaded_corners: Option<&[[DVec3; 3]]>,
) -> Box<[[DVec2; 3]]> {
    (0..surface.triangle_count())
        .map(|t| {
            let t = TriId(t as u32);
            let source = surface.source_triangle(t) as usize;
            let Some(uvs) = per_loaded.get(source) else {
                return [DVec2::ZERO; 3];
            };
            let uvs = uvs.map(DVec2::from_array);
            let order = match loaded_corners.and_then(|c| c.get(source)) {
                Some(&corners) => nearest_order(surface.corners(t), corners),
                None => [0, 1, 2],
            };
            order.map(|k| uvs[k])
        })
        .collect()
}

/// The six orders of three corners, the identity first (it wins ties).
const ORDERS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [1, 2, 0],
    [2, 0, 1],
    [0, 2, 1],
    [2, 1, 0],
    [1, 0, 2],
];

/// The order of `from`'s corners that puts them nearest `to`'s: `from[order[k]]` is
/// matched with `to[k]` (least sum of squared distances).
fn nearest_order(to: [DVec3; 3], from: [DVec3; 3]) -> [usize; 3] {
    let cost = |order: &[usize; 3]| -> f64 {
        (0..3).map(|k| to[k].distance_squared(from[order[k]])).sum()
    };
    ORDERS
        .iter()
        .copied()
        .fold((ORDERS[0], f64::INFINITY), |(best, best_cost), order| {
            let c = cost(&order);
            if c < best_cost {
                (order, c)
            } else {
                (best, best_cost)
            }
        })
        .0
}

/// The texture coordinate at barycentric `weights` of a triangle with corner coordinates
/// `uvs` and barycentric frame `frame`, with the gradients of `u` and `v` over its plane;
/// `None` when the triangle has no area, or its texture map none (three collinear
/// coordinates: the image would be squeezed into a line), or anything is not finite.
///
/// # Real-time
/// A few dozen flops; no allocation, no panic.
#[inline]
pub(super) fn uv_at(frame: &TriFrame, uvs: &[DVec2; 3], weights: [f64; 3]) -> Option<UvPoint> {
    if frame.is_degenerate() || uv_map_is_degenerate(uvs) {
        return None;
    }
    let [a, b, c] = *uvs;
    let uv = weights[0] * a + weights[1] * b + weights[2] * c;
    // The weights of b and c change by dual_b · δ and dual_c · δ along δ in the plane.
    let (db, dc) = (b - a, c - a);
    let grad_u = db.x * frame.dual_b + dc.x * frame.dual_c;
    let grad_v = db.y * frame.dual_b + dc.y * frame.dual_c;
    (uv.is_finite() && grad_u.is_finite() && grad_v.is_finite()).then_some(UvPoint {
        uv,
        grad_u,
        grad_v,
    })
}

/// Whether three texture coordinates span no area: the smallest altitude of their triangle
/// is at most [`DEGENERATE_MAX_RELATIVE_HEIGHT`] of its longest edge, the rule a triangle
/// of the surface is held to (below it the map's inverse keeps too few digits).
fn uv_map_is_degenerate([a, b, c]: &[DVec2; 3]) -> bool {
    let longest2 = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    let twice_area = (*b - *a).perp_dot(*c - *a).abs();
    !(longest2 > 0.0 && twice_area.is_finite())
        || twice_area <= DEGENERATE_MAX_RELATIVE_HEIGHT * longest2
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::MapOptions;
    use crate::mesh::{Mesh, ReadOptions, SurfaceOptions, shapes};
    use crate::scene::{Shape, ShapeError};

    fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
        (a - b).length() <= tol
    }

    #[test]
    fn uv_at_gives_the_affine_map_and_its_gradients() {
        // In the plane z = 0: u = 0.1 + 0.2x, v = 0.2 + 0.2y, so grad u = (0.2, 0, 0) and
        // grad v = (0, 0.2, 0).
        let (a, b, c) = (
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 4.0, 0.0),
        );
        let uvs = [
            DVec2::new(0.1, 0.2),
            DVec2::new(0.5, 0.2),
            DVec2::new(0.1, 1.0),
        ];
        let at = uv_at(&TriFrame::new(a, b, c), &uvs, [0.5, 0.25, 0.25]).unwrap();
        // The point 0.5a + 0.25b + 0.25c = (0.5, 1, 0).
        assert!((at.uv - DVec2::new(0.2, 0.4)).length() < 1e-15, "{at:?}");
        assert!(close(at.grad_u, DVec3::new(0.2, 0.0, 0.0), 1e-15), "{at:?}");
        assert!(close(at.grad_v, DVec3::new(0.0, 0.2, 0.0), 1e-15), "{at:?}");

        // In the tilted plane z = x: u = (x + z) / 2 and v = 2y, whose gradients
        // (0.5, 0, 0.5) and (0, 2, 0) lie in the plane (normal (−1, 0, 1) / √2).
        let (a, b, c) = (DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0), DVec3::Y);
        let uvs = [DVec2::ZERO, DVec2::new(1.0, 0.0), DVec2::new(0.0, 2.0)];
        let at = uv_at(&TriFrame::new(a, b, c), &uvs, [0.2, 0.3, 0.5]).unwrap();
        assert!((at.uv - DVec2::new(0.3, 1.0)).length() < 1e-15, "{at:?}");
        assert!(close(at.grad_u, DVec3::new(0.5, 0.0, 0.5), 1e-15), "{at:?}");
        assert!(close(at.grad_v, DVec3::new(0.0, 2.0, 0.0), 1e-15), "{at:?}");

        // No area in the image, or none on the surface: no map.
        let flat = [DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(2.0, 2.0)];
        assert_eq!(uv_at(&TriFrame::new(a, b, c), &flat, [1.0, 0.0, 0.0]), None);
        let line = TriFrame::new(a, DVec3::X, DVec3::new(2.0, 0.0, 0.0));
        assert_eq!(uv_at(&line, &uvs, [1.0, 0.0, 0.0]), None);
    }

    /// A 0.1 m square in z = 0 with texture coordinates u = 10x, v = 5y + 0.25 at its
    /// corners, as OBJ whose second triangle is wound clockwise seen from +z.
    const SQUARE_OBJ: &str = "v 0 0 0\nv 0.1 0 0\nv 0.1 0.1 0\nv 0 0.1 0\n\
                              vt 0 0.25\nvt 1 0.25\nvt 1 0.75\nvt 0 0.75\n\
                              f 1/1 2/2 3/3\nf 1/1 4/4 3/3\n";

    #[test]
    fn a_read_shape_keeps_each_corners_coordinate_whatever_the_winding() {
        let shape = Shape::read(
            "square.obj",
            SQUARE_OBJ.as_bytes(),
            &ReadOptions::default(),
            &MapOptions::default(),
        )
        .unwrap();
        assert!(shape.has_texture_coords());
        let surface = shape.surface();
        for t in 0..surface.triangle_count() {
            let t = TriId(t as u32);
            let corners = surface.corners(t);
            for weights in [[1.0, 0.0, 0.0], [0.2, 0.5, 0.3], [0.0, 0.1, 0.9]] {
                let p: DVec3 = (0..3).map(|k| weights[k] * corners[k]).sum();
                let at = shape.uv_at(t, weights).unwrap();
                let expected = DVec2::new(10.0 * p.x, 5.0 * p.y + 0.25);
                assert!((at.uv - expected).length() < 1e-6, "{t:?} {p}: {at:?}");
                assert!(close(at.grad_u, DVec3::new(10.0, 0.0, 0.0), 1e-5), "{at:?}");
                assert!(close(at.grad_v, DVec3::new(0.0, 5.0, 0.0), 1e-5), "{at:?}");
            }
        }
        assert_eq!(shape.uv_at(TriId(2), [1.0, 0.0, 0.0]), None);
        let plain = Shape::read(
            "square.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            &ReadOptions::default(),
            &MapOptions::default(),
        )
        .unwrap();
        assert!(!plain.has_texture_coords());
        assert_eq!(plain.uv_at(TriId(0), [1.0, 0.0, 0.0]), None);
    }

    #[test]
    fn a_turned_over_triangle_takes_its_corners_coordinates_by_place() {
        // The loaded square, and a surface of it whose second triangle is turned over (as a
        // repair for a consistent orientation does): its corners come in another order.
        let loaded = Mesh {
            vertices: vec![
                DVec3::ZERO,
                DVec3::new(0.1, 0.0, 0.0),
                DVec3::new(0.1, 0.1, 0.0),
                DVec3::new(0.0, 0.1, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 3, 2]],
        };
        let mut turned = loaded.clone();
        turned.triangles[1] = [0, 2, 3];
        let surface = Surface::new(turned, &SurfaceOptions::default()).unwrap();
        let uv_of = |p: DVec3| [10.0 * p.x, 5.0 * p.y + 0.25];
        let per_loaded: Vec<[[f64; 2]; 3]> = (0..2).map(|t| loaded.corners(t).map(uv_of)).collect();
        let corners: Vec<[DVec3; 3]> = (0..2).map(|t| loaded.corners(t)).collect();
        let by_place = in_surface_order(&surface, &per_loaded, Some(&corners));
        for t in 0..2 {
            let expected = surface
                .corners(TriId(t))
                .map(|p| DVec2::from_array(uv_of(p)));
            assert_eq!(by_place[t as usize], expected, "triangle {t}");
        }
    }

    #[test]
    fn given_coordinates_follow_the_surfaces_own_order() {
        // A sphere's triangles, shuffled by the surface's spatial order: u = x + 2y,
        // v = z − y at every corner, so the coordinate at a point is that function, and
        // its gradients are those of the function projected into each triangle's plane.
        let mesh = shapes::sphere(0.05, 2);
        let (g_u, g_v) = (DVec3::new(1.0, 2.0, 0.0), DVec3::new(0.0, -1.0, 1.0));
        let per_loaded: Vec<[[f64; 2]; 3]> = (0..mesh.triangles.len())
            .map(|t| mesh.corners(t).map(|p| [g_u.dot(p), g_v.dot(p)]))
            .collect();
        let shape = Shape::from_mesh("sphere", mesh, &MapOptions::default())
            .unwrap()
            .with_texture_coords(per_loaded)
            .unwrap();
        let surface = shape.surface();
        assert!(
            (0..surface.triangle_count() as u32).any(|t| surface.source_triangle(TriId(t)) != t)
        );
        let mut without = 0;
        for t in 0..surface.triangle_count() {
            let t = TriId(t as u32);
            let centroid = surface.corners(t).iter().sum::<DVec3>() / 3.0;
            let n = surface.frame(t).normal;
            // The image of a triangle has area |n · (g_u × g_v)| times its own: none for
            // a triangle standing along g_u × g_v.
            let Some(at) = shape.uv_at(t, [1.0 / 3.0; 3]) else {
                assert!(n.dot(g_u.cross(g_v)).abs() < 1e-6, "{t:?}");
                without += 1;
                continue;
            };
            let expected = DVec2::new(g_u.dot(centroid), g_v.dot(centroid));
            assert!((at.uv - expected).length() < 1e-12, "{t:?}");
            assert!(close(at.grad_u, g_u - n * n.dot(g_u), 1e-9), "{t:?}");
            assert!(close(at.grad_v, g_v - n * n.dot(g_v), 1e-9), "{t:?}");
        }
        assert!(without * 20 < surface.triangle_count());
    }

    #[test]
    fn given_coordinates_are_checked() {
        let mesh = shapes::sphere(0.05, 1);
        let n = mesh.triangles.len();
        let shape = Shape::from_mesh("sphere", mesh, &MapOptions::default()).unwrap();
        let err = shape
            .with_texture_coords(vec![[[0.0; 2]; 3]; n - 1])
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "texture coordinates for {} triangles, but the shape has {n} triangles",
                n - 1
            )
        );
        let shape =
            Shape::from_mesh("sphere", shapes::sphere(0.05, 1), &MapOptions::default()).unwrap();
        let mut uvs = vec![[[0.0; 2]; 3]; n];
        uvs[7][2][1] = f64::NAN;
        let err = shape.with_texture_coords(uvs).unwrap_err();
        assert_eq!(
            err,
            ShapeError::TextureCoordNotFinite {
                triangle: 7,
                corner: 2
            }
        );
        assert_eq!(
            err.to_string(),
            "triangle 7, corner 2: a texture coordinate is not a finite number"
        );
    }

    #[test]
    fn nearest_order_undoes_any_permutation() {
        let to = [DVec3::X, DVec3::Y, DVec3::new(0.3, 0.2, 1.0)];
        for order in ORDERS {
            // from[order[k]] = to[k].
            let mut from = [DVec3::ZERO; 3];
            for k in 0..3 {
                from[order[k]] = to[k] + DVec3::splat(1e-9);
            }
            assert_eq!(nearest_order(to, from), order);
        }
    }

    #[test]
    fn a_collinear_or_repeated_texture_map_is_degenerate() {
        let uv = |x, y| DVec2::new(x, y);
        assert!(!uv_map_is_degenerate(&[
            uv(0.0, 0.0),
            uv(1.0, 0.0),
            uv(0.0, 1.0)
        ]));
        assert!(uv_map_is_degenerate(&[
            uv(0.0, 0.0),
            uv(1.0, 1.0),
            uv(2.0, 2.0)
        ]));
        assert!(uv_map_is_degenerate(&[uv(0.5, 0.5); 3]));
        assert!(uv_map_is_degenerate(&[
            uv(0.0, 0.0),
            uv(f64::NAN, 0.0),
            uv(0.0, 1.0)
        ]));
    }
}
