//! Textures as felt through the servo: sliding over a sine texture is felt at the speed
//! over the wavelength (a spectrum's peak), the force's change per tick stays within what
//! the texture's slope and curvature allow, and the texture never gives back more work
//! than it took over a closed path (passivity).

mod feel;

use std::sync::Arc;

use haphe::DVec3;
use haphe::scene::Texture;

use feel::{Run, peak_near, slab_scene, spectrum, work_around};

const STIFFNESS: f64 = 500.0;

fn sine() -> Texture {
    "sine:0.0002:0.002".parse().expect("a valid texture")
}

/// The path: down onto the slab's top (z = 0) 1 mm deep, then along x at `speed`.
fn slide(speed: f64, seconds: f64) -> Vec<(f64, DVec3)> {
    let start = DVec3::new(-0.06, 0.0, 0.003);
    let down = DVec3::new(-0.06, 0.0, -0.001);
    let mut keys = vec![(0.0, start), (0.2, down)];
    let steps = 200;
    for i in 1..=steps {
        let t = seconds * i as f64 / steps as f64;
        keys.push((0.2 + t, down + DVec3::X * (speed * t)));
    }
    keys
}

/// Acceptance 1: sliding at 50 mm/s over `sine:0.0002:0.002`, the force's spectrum peaks
/// at 25 Hz; without the texture it has no such peak.
#[test]
fn sliding_over_a_sine_texture_is_felt_at_speed_over_wavelength() {
    let rate = 1000.0;
    let keys = slide(0.05, 2.4);
    let textured = Run::new(slab_scene(Some(sine()), &[]), rate).keys(&keys);
    let plain = Run::new(slab_scene(None, &[]), rate).keys(&keys);
    // Two seconds of sliding, from 0.3 s.
    let window = |r: &[haphe::servo::TickRecord]| -> Vec<f64> {
        r.iter()
            .filter(|r| r.t >= 0.3)
            .take(2000)
            .map(|r| r.force.z)
            .collect()
    };
    let (tz, pz) = (window(&textured), window(&plain));
    assert_eq!(tz.len(), 2000);
    assert!(
        tz.iter().all(|&f| f > 0.0),
        "in contact all along: {:?}",
        tz.iter().copied().fold(f64::INFINITY, f64::min)
    );
    let (freqs, t_mag) = spectrum(&tz, rate);
    let (_, p_mag) = spectrum(&pz, rate);
    let (f, m) = peak_near(&freqs, &t_mag, 1.0, rate / 2.0);
    assert!((f - 25.0).abs() <= 0.5, "the peak is at {f} Hz");
    // The ridges of the sine across x have amplitude A/3: the force's, k A / 3.
    let expected = STIFFNESS * 0.0002 / 3.0;
    assert!(
        (m - expected).abs() < 0.1 * expected,
        "amplitude {m} N, expected {expected}"
    );
    let (_, plain_there) = peak_near(&freqs, &p_mag, 24.0, 26.0);
    assert!(
        plain_there < 1e-3 * m,
        "untextured: {plain_there} N at 25 Hz"
    );
}

/// The force's change from one tick to the next while sliding at 50 mm/s is within
/// `k v dt (A ω (1 + A ω) + (d + A) A ω²)`: the texture's height and slope change no
/// faster than its slope and curvature times the speed (ω = 2π / L), at 1 and 10 kHz.
#[test]
fn the_force_changes_per_tick_within_the_textures_slope_and_curvature() {
    let (a, l, v, depth) = (0.0002, 0.002, 0.05, 0.001);
    let w = std::f64::consts::TAU / l;
    for rate in [1000.0, 10_000.0] {
        let keys = slide(v, 1.0);
        let records = Run::new(slab_scene(Some(sine()), &[]), rate).keys(&keys);
        let sliding: Vec<_> = records.iter().filter(|r| r.t >= 0.3).collect();
        let largest = sliding
            .windows(2)
            .map(|p| p[1].force.distance(p[0].force))
            .fold(0.0, f64::max);
        let dt = 1.0 / rate;
        let bound = STIFFNESS * v * dt * (a * w * (1.0 + a * w) + (depth + a) * a * w * w);
        assert!(
            largest <= bound,
            "{rate} Hz: {largest} N per tick, bound {bound}"
        );
        assert!(
            largest > 0.1 * bound,
            "{rate} Hz: the texture is felt ({largest} N)"
        );
    }
}

/// Acceptance 3 (textures): around closed paths that go in and out of contact, and that
/// stay in contact at changing depth, the work the force does on the hand is at most 0
/// (1e-8 J: the discretisation of a turn at 10 kHz, measured without a texture, is
/// below 1e-9 J), both ways round, for the sine and the noise textures.
/// The same path with the force's part across the normal left out (a texture rendered as
/// a height only) does positive work one way round: the check can fail.
#[test]
fn a_texture_gives_back_no_more_work_than_it_took() {
    let textures = [
        sine(),
        "noise:0.0001:0.0015".parse().expect("a valid texture"),
    ];
    for texture in textures {
        for (centre, radius) in [
            // Half in contact.
            (DVec3::new(0.0, 0.0, 0.0), 0.002),
            // Always in contact, at depths from 0.5 to 2.5 mm.
            (DVec3::new(0.0, 0.0, -0.0015), 0.001),
        ] {
            let mut normal_only = Vec::new();
            for turn in [1.0, -1.0] {
                let scene = slab_scene(Some(texture.clone()), &[]);
                let (work, records) = work_around(scene, centre, radius, turn);
                assert!(
                    work <= 1e-8,
                    "{texture:?} around {centre} (r {radius}, turn {turn}): {work} J"
                );
                let heights: Vec<DVec3> = records.iter().map(|r| DVec3::Z * r.force.z).collect();
                normal_only.push(feel::work_of(&records, &heights));
            }
            let most = normal_only.iter().copied().fold(f64::MIN, f64::max);
            assert!(most > 1e-6, "{texture:?}: the height alone does {most} J");
        }
    }
}

/// Acceptance 4: a height image on a textured OBJ (both written here: a 10 cm square with
/// texture coordinates over the whole image, and a 64 × 64 PNG, black but for a bright
/// spot at pixel (48, 16)) is felt where the image says: pressing 2 mm into the square
/// over a grid of points, the force is largest over the spot, at the point whose texture
/// coordinates are that pixel's centre (u = 48.5 / 64, v = 1 − 16.5 / 64), within a pixel.
#[test]
fn an_image_texture_is_felt_where_the_image_says() {
    use haphe::map::MapOptions;
    use haphe::mesh::ReadOptions;
    use haphe::proxy::{Proxy, ProxyOptions};
    use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};

    let dir = std::env::temp_dir().join(format!("haphe-image-texture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let (side, spot) = (64u32, (48.0, 16.0));
    let png = dir.join("spot.png");
    let pixels = image::GrayImage::from_fn(side, side, |x, y| {
        let r2 = (f64::from(x) - spot.0).powi(2) + (f64::from(y) - spot.1).powi(2);
        image::Luma([(255.0 * (-r2 / 8.0).exp()).round() as u8])
    });
    pixels.save(&png).expect("the PNG written");
    let obj = "v -0.05 -0.05 0\nv 0.05 -0.05 0\nv 0.05 0.05 0\nv -0.05 0.05 0\n\
               vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    let shape = Shape::read(
        "square.obj",
        obj.as_bytes(),
        &ReadOptions::default(),
        &MapOptions::default(),
    )
    .expect("a textured square");
    assert!(shape.has_texture_coords());
    let texture: Texture = format!("image:{}:0.0005", png.display())
        .parse()
        .expect("the image texture");
    let mut scene = Scene::local(1);
    let square = SceneObject::new(
        ObjectId(0),
        Arc::new(shape),
        Pose::IDENTITY,
        Material::default(),
    )
    .with_texture(texture);
    scene.insert(square).map_err(|(e, _)| e).expect("room");

    let depth = 0.002;
    let press = |x: f64, y: f64| {
        let above = DVec3::new(x, y, 0.003);
        let mut proxy = Proxy::new(above, ProxyOptions::default());
        proxy.tick(&scene, above, DVec3::ZERO);
        proxy
            .tick(&scene, DVec3::new(x, y, -depth), DVec3::ZERO)
            .force
            .z
    };
    let step = 0.0005;
    let mut strongest = (f64::MIN, 0.0, 0.0);
    let mut weakest = f64::MAX;
    for i in 0..=100 {
        for j in 0..=100 {
            let (x, y) = (-0.01 + step * f64::from(i), -0.01 + step * f64::from(j));
            let f = press(x, y);
            weakest = weakest.min(f);
            if f > strongest.0 {
                strongest = (f, x, y);
            }
        }
    }
    let (u, v) = (
        (spot.0 + 0.5) / f64::from(side),
        1.0 - (spot.1 + 0.5) / f64::from(side),
    );
    let expected = (-0.05 + 0.1 * u, -0.05 + 0.1 * v);
    let pixel = 0.1 / f64::from(side);
    assert!(
        (strongest.1 - expected.0).abs() <= pixel && (strongest.2 - expected.1).abs() <= pixel,
        "strongest at ({}, {}), the spot's pixel at {expected:?}",
        strongest.1,
        strongest.2
    );
    // White is A above the plane, black A below: k (d ± A) with k 500 N/m, the depth
    // counted from the proxy a skin (1 µm, 0.5 mN) above the surface. The grid's nearest
    // point to the spot is a fifth of a pixel from it, where the bilinear value is within
    // 5 % of the peak.
    let (k, skin) = (500.0, 1e-6);
    let top = k * (depth + skin + 0.0005);
    assert!(
        strongest.0 <= top + 1e-9 && strongest.0 > top - 0.05 * k * 2.0 * 0.0005,
        "{}",
        strongest.0
    );
    assert!(
        (weakest - k * (depth + skin - 0.0005)).abs() < 1e-9,
        "{weakest}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
