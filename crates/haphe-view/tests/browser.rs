//! End to end, in a real headless browser (Chromium, software WebGL, driven over the
//! DevTools protocol): the page loads without console errors and draws the scene; mouse
//! events push the device point into a sphere and the server reports contact with a force
//! pointing out of it; a recorded trace replays to its last tick; with two devices, each
//! one's tool is drawn; the scene's effect zones are drawn where they act.
//!
//! Needs Chromium (`apt-get install chromium`; `.ci/run` installs it). With
//! `HAPHE_VIEW_SCREENSHOT=docs/view.png` the test also writes the screenshot of the
//! contact for the documentation.

mod support;

use std::time::{Duration, Instant};

use haphe::DVec3;
use haphe::proxy::ProxyOptions;
use haphe::scene::{Effect, Material, ObjectId, Pose, Scene, Zone};
use haphe::servo::{
    Motion, ObjectMotion, PathKind, RealtimeOptions, ScriptedDevice, Servo, ServoOptions,
    Trajectory, scene_bounds, scripted_path,
};
use haphe_view::{LiveSource, Model, MouseDevice, Source, Trace, ViewOptions, ViewServer};
use serde_json::Value;
use support::cdp::{Browser, decode_png};

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 800;

fn sphere_scene() -> Scene {
    let material = Material::builder()
        .stiffness(600.0)
        .damping(1.0)
        .friction(0.3, 0.2)
        .build()
        .expect("a valid material");
    haphe::verify::sphere_scene(2_000, material).expect("the sphere scene")
}

/// The sphere scene's box, centre and radius.
fn sphere_bounds(scene: &Scene) -> (DVec3, DVec3, DVec3, f64) {
    let (lo, hi) = scene_bounds(scene).expect("bounds");
    (lo, hi, 0.5 * (lo + hi), 0.5 * (hi.z - lo.z))
}

/// The view of a live run at 1 kHz at normal priority (the test machine is shared) of a
/// mouse device at `start`, free in the scene's box grown by its size each way; the
/// page's mouse moves it when `mouse`.
fn live_view(
    model: Model,
    scene: Scene,
    start: DVec3,
    (motions, seconds): (Vec<ObjectMotion>, Option<f64>),
    mouse: bool,
    title: &str,
    servo: ServoOptions,
) -> ViewServer {
    let (lo, hi) = scene_bounds(&scene).expect("bounds");
    let (device, handle) = MouseDevice::new(start, lo - (hi - lo), hi + (hi - lo));
    let source = LiveSource {
        device: Box::new(device),
        scene,
        options: servo,
        motions,
        seconds,
        realtime: RealtimeOptions::default().with_realtime_priority(false),
        clock: None,
        others: Vec::new(),
        on_record: None,
    };
    ViewServer::start(
        model,
        Source::Live {
            source: Box::new(source),
            mouse: mouse.then_some(handle),
        },
        &options(title),
    )
    .expect("the view starts")
}

/// The trace of a simulated press of `ticks` ticks at 1 kHz into the sphere, whose
/// objects move by `motions`, read back from its CSV as file `name`.
fn recorded_press(ticks: u32, motions: Vec<ObjectMotion>, name: &str) -> Trace {
    let scene = sphere_scene();
    let path = scripted_path(PathKind::Press, &scene, f64::from(ticks) / 1000.0, 1).expect("path");
    let mut servo =
        Servo::new(ScriptedDevice::new(path), scene, ServoOptions::default()).expect("servo");
    servo.set_motions(motions);
    let mut csv = Vec::new();
    haphe::servo::write_csv_header(&mut csv).expect("header");
    servo.run_simulated(u64::from(ticks), |r| r.write_csv(&mut csv).expect("row"));
    Trace::read(name, csv.as_slice()).expect("reads back")
}

/// Opens `view`, a replay, and waits until it has played to its last tick.
fn replay_to_the_end(browser: &mut Browser, view: &ViewServer) {
    browser.navigate(&view.url());
    browser.wait_for(
        "!!(window.haphe && window.haphe.replay && window.haphe.replay.atEnd)",
        Duration::from_secs(30),
        "the replay to reach its last tick",
    );
}

/// Where world point `p` is on the page.
fn project(browser: &mut Browser, p: DVec3) -> (f64, f64) {
    xy(&browser.eval(&format!("window.haphe.project({}, {}, {})", p.x, p.y, p.z)))
}

fn options(title: &str) -> ViewOptions {
    ViewOptions {
        port: 0,
        title: title.into(),
    }
}

fn xy(v: &Value) -> (f64, f64) {
    (
        v[0].as_f64().expect("x on the page"),
        v[1].as_f64().expect("y on the page"),
    )
}

#[test]
fn the_view_draws_the_scene_follows_the_mouse_and_replays_a_trace() {
    let started = Instant::now();
    let scene = sphere_scene();
    let (lo, hi, centre, radius) = sphere_bounds(&scene);
    let model = Model::from_scene(&scene, &["sphere".to_string()]);
    let start = DVec3::new(centre.x, centre.y, hi.z + 0.2 * radius);
    let view = live_view(
        model.clone(),
        scene,
        start,
        (Vec::new(), None),
        true,
        "haphe view: the mouse on a sphere",
        ServoOptions::default(),
    );

    let mut browser = Browser::start(WIDTH, HEIGHT);
    browser.navigate(&view.url());
    browser.wait_for(
        "!!(window.haphe && window.haphe.ready && window.haphe.frames > 2 && window.haphe.connected)",
        Duration::from_secs(40),
        "the page to draw and receive frames",
    );

    // The floor grid says its scale: 30 cells over three times the scene's largest side.
    let text = browser.eval("document.getElementById('grid-scale').textContent");
    let text = text.as_str().expect("text").to_string();
    let cell_mm = (hi - lo).max_element() * 3.0 / 30.0 * 1e3;
    let shown: f64 = text
        .trim_start_matches("1 cell = ")
        .trim_end_matches(" mm")
        .parse()
        .unwrap_or_else(|_| panic!("{text:?}"));
    assert!(
        (shown - cell_mm).abs() <= 5e-3 * cell_mm,
        "{text} vs {cell_mm} mm"
    );
    // The chart has a legend naming both lines, each in its line's colour.
    let legend = browser.eval(
        "[...document.querySelectorAll('#chart-legend [data-series]')].map(e => e.dataset.series + ':' + e.textContent + ':' + getComputedStyle(e).color).join('|')",
    );
    let legend = legend.as_str().expect("text");
    assert_eq!(
        legend,
        "force:force (N, left axis):rgb(255, 179, 71)|penetration:penetration (mm, right axis):rgb(108, 182, 255)"
    );

    // The scene is drawn: the sphere's grey-blue fills a good part of the middle of the
    // page, which is otherwise the dark background.
    let (w, h, pixels) = decode_png(&browser.screenshot());
    let middle = |x: u32, y: u32| x > w / 4 && x < 3 * w / 4 && y > h / 8 && y < 7 * h / 8;
    let (mut object, mut total) = (0usize, 0usize);
    for (i, p) in pixels.iter().enumerate() {
        let (x, y) = (i as u32 % w, i as u32 / w);
        if middle(x, y) {
            total += 1;
            object += usize::from(object_colour(*p));
        }
    }
    let covered = object as f64 / total as f64;
    println!(
        "screenshot {w}x{h}: {:.0} % of the middle is the sphere",
        100.0 * covered
    );
    assert!(covered > 0.15, "the sphere is not drawn: {covered}");
    let before = view.latest().expect("frames");
    assert!(before.object.is_none() && before.force().length() == 0.0);

    // Mouse events move the device point from above the sphere to its centre on the page.
    let from = project(&mut browser, start);
    let to = project(&mut browser, centre);
    let steps = 40;
    for k in 0..=steps {
        let a = f64::from(k) / f64::from(steps);
        browser.mouse_move(from.0 + a * (to.0 - from.0), from.1 + a * (to.1 - from.1));
        std::thread::sleep(Duration::from_millis(25));
    }
    std::thread::sleep(Duration::from_millis(400));
    let f = view.latest().expect("frames");
    println!("after the mouse: {f:?}");
    assert_eq!(f.object, Some(0), "the server reports no contact: {f:?}");
    let hip = DVec3::from_array(f.hip);
    let proxy = DVec3::from_array(f.proxy);
    let force = f.force();
    assert!(
        (hip - centre).length() < 0.95 * radius,
        "the device point is not in: {f:?}"
    );
    assert!(
        ((proxy - centre).length() - radius).abs() < 0.03 * radius,
        "the proxy is not on the surface: {f:?}"
    );
    assert!(force.length() > 1.0, "too little force: {f:?}");
    let outward = force.normalize().dot((proxy - centre).normalize());
    assert!(outward > 0.8, "the force does not point out: {outward}");
    // The page shows the contact too.
    browser.wait_for(
        "document.getElementById('touch').textContent.includes('triangle') && window.haphe.normal !== null",
        Duration::from_secs(5),
        "the page to show the contact",
    );
    if let Some(path) = std::env::var_os("HAPHE_VIEW_SCREENSHOT") {
        std::fs::write(&path, browser.screenshot()).expect("write the screenshot");
        println!("wrote {}", std::path::Path::new(&path).display());
    }
    let run = view.stop().expect("stops").expect("a live run");
    let stats = run.servo.stats();
    println!(
        "servo: {} ticks, compute p50 {} ns p99 {} ns",
        stats.ticks,
        stats.compute.quantile(0.5),
        stats.compute.quantile(0.99)
    );
    assert!(stats.ticks > 1000 && stats.contact_ticks > 100);

    // Replay: a short press recorded in simulation plays to its last tick.
    let trace = recorded_press(600, Vec::new(), "press.csv");
    let rows = trace.rows.len();
    assert!(trace.rows.iter().any(|r| r.object.is_some()));
    let view = ViewServer::start(model, Source::Replay(trace), &options("replay"))
        .expect("the replay view starts");
    replay_to_the_end(&mut browser, &view);
    let r = browser.eval("window.haphe.replay");
    assert_eq!(r["index"].as_u64(), Some(rows as u64 - 1), "{r}");
    assert_eq!(
        browser.eval("document.getElementById('clock').textContent.startsWith('tick 600 / 600')"),
        Value::Bool(true)
    );
    view.stop().expect("stops");

    let errors = std::mem::take(&mut browser.errors);
    assert!(errors.is_empty(), "console errors: {errors:#?}");
    println!("browser test took {:.1} s", started.elapsed().as_secs_f64());
}

/// Whether pixel `px` is the object's grey-blue (not the dark background).
fn object_colour(px: [u8; 4]) -> bool {
    let lum = (u32::from(px[0]) + u32::from(px[1]) + u32::from(px[2])) / 3;
    lum > 70 && px[2] > px[0]
}

/// Whether the pixel at page point `p` is the object's grey-blue (not the background).
fn is_object(pixels: &[[u8; 4]], w: u32, p: (f64, f64)) -> bool {
    object_colour(pixels[(p.1 as u32 * w + p.0 as u32) as usize])
}

#[test]
fn an_object_moved_by_script_is_drawn_where_it_is_live_and_in_replay() {
    let scene = sphere_scene();
    let (_, hi, centre, radius) = sphere_bounds(&scene);
    let model = Model::from_scene(&scene, &["sphere".to_string()]);
    // The sphere slides 2 radii along x in one second, then the run ends; the device
    // point waits far above it.
    let seconds = 1.0;
    let motions = vec![ObjectMotion {
        id: ObjectId(0),
        base: Pose::IDENTITY,
        motion: Motion::Linear {
            velocity: DVec3::new(2.0 * radius / seconds, 0.0, 0.0),
        },
    }];
    let start = DVec3::new(centre.x, centre.y, hi.z + 1.5 * radius);
    let view = live_view(
        model.clone(),
        scene,
        start,
        (motions.clone(), Some(seconds)),
        false,
        "a sliding sphere",
        ServoOptions::default(),
    );
    let mut browser = Browser::start(WIDTH, HEIGHT);
    browser.navigate(&view.url());
    browser.wait_for(
        "!!(window.haphe && window.haphe.ready && window.haphe.frame && window.haphe.frame.ended)",
        Duration::from_secs(40),
        "the run to end on the page",
    );
    // Drawn where the last frame's tick had it: the servo's pose at that time.
    let frame = browser.eval("window.haphe.frame");
    let drawn = browser.eval("window.haphe.drawn[0]");
    let t = frame["t"].as_f64().expect("t");
    let expected = motions[0].pose_at(t).translation();
    let x = drawn["translation"][0].as_f64().expect("drawn x");
    println!("live: t = {t} s, drawn at x = {x}, expected {}", expected.x);
    assert!(t > 0.9 * seconds, "{frame}");
    assert!((x - expected.x).abs() < 1e-9, "{drawn} against {expected}");
    // And on the page: the sphere's colour where it is now, the background where it was.
    let now = project(&mut browser, centre + expected);
    let before = project(&mut browser, centre);
    let (w, _, pixels) = decode_png(&browser.screenshot());
    assert!(
        is_object(&pixels, w, now),
        "no sphere where it is now, {now:?}"
    );
    assert!(
        !is_object(&pixels, w, before),
        "the sphere is still drawn where it started, {before:?}"
    );
    view.stop().expect("stops");

    // Replay: a simulated run of the same motion, scrubbed to its end.
    let trace = recorded_press(500, motions.clone(), "slide.csv");
    let last_t = trace.rows.last().expect("rows").t;
    let view = ViewServer::start(
        model.with_motions(motions.clone()),
        Source::Replay(trace),
        &options("replay of a sliding sphere"),
    )
    .expect("the replay view starts");
    replay_to_the_end(&mut browser, &view);
    let drawn = browser.eval("window.haphe.drawn[0]");
    let x = drawn["translation"][0].as_f64().expect("drawn x");
    let expected = motions[0].pose_at(last_t).translation();
    println!(
        "replay: t = {last_t} s, drawn at x = {x}, expected {}",
        expected.x
    );
    // The replay's poses travel as f32.
    assert!((x - expected.x).abs() < 1e-6, "{drawn} against {expected}");
    view.stop().expect("stops");
    let errors = std::mem::take(&mut browser.errors);
    assert!(errors.is_empty(), "console errors: {errors:#?}");
}

/// Whether pixel `px` is the tool's green (not the object's grey-blue, the background, the
/// orange device point or the white line).
fn tool_colour(px: [u8; 4]) -> bool {
    let [r, g, b, _] = px.map(i32::from);
    g > r + 40 && g > b + 20
}

#[test]
fn the_tool_is_drawn_as_a_sphere_of_its_radius() {
    let scene = sphere_scene();
    let (_, hi, centre, radius) = sphere_bounds(&scene);
    let tool = 0.3 * radius;
    let model = Model::from_scene(&scene, &["sphere".to_string()]);
    // Free, above the sphere (the tool clear of it): the proxy is the device point, the
    // tool's centre.
    let start = DVec3::new(centre.x, centre.y, hi.z + 0.6 * radius);
    let proxy = ProxyOptions::default()
        .with_tool_radius(tool)
        .expect("a radius in its domain");
    let view = live_view(
        model.clone(),
        scene,
        start,
        (Vec::new(), None),
        false,
        "a tool above a sphere",
        ServoOptions::default().with_proxy(proxy),
    );
    let mut browser = Browser::start(WIDTH, HEIGHT);
    browser.navigate(&view.url());
    browser.wait_for(
        "!!(window.haphe && window.haphe.ready && window.haphe.frames > 2)",
        Duration::from_secs(40),
        "the page to draw and receive frames",
    );
    // The page learns the servo's radius and draws a sphere of it.
    assert_eq!(
        browser.eval("window.haphe.info.tool_radius").as_f64(),
        Some(tool)
    );
    let drawn = browser.eval("window.haphe.tool");
    assert_eq!(drawn["drawn"].as_f64(), Some(tool), "{drawn}");
    let frame = browser.eval("window.haphe.frame");
    let p: Vec<f64> = (0..3)
        .map(|i| frame["proxy"][i].as_f64().expect("proxy"))
        .collect();
    let p = DVec3::new(p[0], p[1], p[2]);
    assert!((p - start).length() < 1e-9, "the proxy at {p}, not {start}");
    // On the screen: the tool's green within its radius of the centre (beside the device
    // point's marker), not beyond it. World points along x, which the camera sees nearly
    // across its line of sight (at most 4 % shorter).
    let (w, _, pixels) = decode_png(&browser.screenshot());
    let at = |q: (f64, f64)| pixels[(q.1 as u32 * w + q.0 as u32) as usize];
    for side in [-1.0, 1.0] {
        let inside = project(&mut browser, p + DVec3::X * (side * 0.7 * tool));
        let outside = project(&mut browser, p + DVec3::X * (side * 1.3 * tool));
        assert!(
            tool_colour(at(inside)),
            "no tool at {inside:?}: {:?}",
            at(inside)
        );
        assert!(
            !tool_colour(at(outside)),
            "the tool reaches {outside:?}: {:?}",
            at(outside)
        );
    }
    let text = browser.eval("document.getElementById('device').textContent");
    assert!(
        text.as_str()
            .is_some_and(|t| t.contains("tool: a sphere of radius")),
        "{text}"
    );
    view.stop().expect("stops");

    // A replay draws the radius its model gives.
    let trace = recorded_press(50, Vec::new(), "press.csv");
    let view = ViewServer::start(
        model.with_tool_radius(tool),
        Source::Replay(trace),
        &options("replay with a tool"),
    )
    .expect("the replay view starts");
    replay_to_the_end(&mut browser, &view);
    let drawn = browser.eval("window.haphe.tool");
    assert_eq!(drawn["radius"].as_f64(), Some(tool), "{drawn}");
    assert_eq!(drawn["drawn"].as_f64(), Some(tool), "{drawn}");
    view.stop().expect("stops");
    let errors = std::mem::take(&mut browser.errors);
    assert!(errors.is_empty(), "console errors: {errors:#?}");
}

/// The blue of the second device's tool (not the sphere's grey-blue, nor the first
/// device's green).
fn second_tool_colour(px: [u8; 4]) -> bool {
    let [r, g, b, _] = px.map(i32::from);
    b > r + 60 && b > g + 30
}

#[test]
fn every_devices_tool_is_drawn() {
    let scene = sphere_scene();
    let (_, hi, centre, radius) = sphere_bounds(&scene);
    let model = Model::from_scene(&scene, &["sphere".to_string()]);
    // Two devices held still, free above the sphere on either side: the second with a
    // tool of its own radius.
    let a = DVec3::new(centre.x - 0.5 * radius, centre.y, hi.z + 0.6 * radius);
    let b = DVec3::new(centre.x + 0.5 * radius, centre.y, hi.z + 0.6 * radius);
    let tool = 0.3 * radius;
    let second = ServoOptions::default().with_proxy(
        ProxyOptions::default()
            .with_tool_radius(tool)
            .expect("a radius in its domain"),
    );
    let source = LiveSource {
        device: Box::new(ScriptedDevice::new(Trajectory::still(a))),
        scene,
        options: ServoOptions::default(),
        motions: Vec::new(),
        seconds: None,
        realtime: RealtimeOptions::default().with_realtime_priority(false),
        clock: None,
        others: vec![(Box::new(ScriptedDevice::new(Trajectory::still(b))), second)],
        on_record: None,
    };
    let view = ViewServer::start(
        model,
        Source::Live {
            source: Box::new(source),
            mouse: None,
        },
        &options("two devices above a sphere"),
    )
    .expect("the view starts");
    let mut browser = Browser::start(WIDTH, HEIGHT);
    browser.navigate(&view.url());
    browser.wait_for(
        "!!(window.haphe && window.haphe.ready && window.haphe.others.length === 1)",
        Duration::from_secs(40),
        "the page to draw the second device",
    );
    let other = browser.eval("window.haphe.others[0]");
    let p: Vec<f64> = (0..3)
        .map(|i| other["proxy"][i].as_f64().expect("proxy"))
        .collect();
    assert!(
        (DVec3::new(p[0], p[1], p[2]) - b).length() < 1e-9,
        "{other}"
    );
    assert_eq!(other["drawn"].as_f64(), Some(tool), "{other}");
    // On the screen: the second tool's blue at its centre and within its radius, not
    // beyond; the first device's tool (a point, the green marker) at its own place.
    let (w, _, pixels) = decode_png(&browser.screenshot());
    let at = |q: (f64, f64)| pixels[(q.1 as u32 * w + q.0 as u32) as usize];
    for side in [-1.0, 1.0] {
        let inside = project(&mut browser, b + DVec3::X * (side * 0.5 * tool));
        let outside = project(&mut browser, b + DVec3::X * (side * 1.5 * tool));
        assert!(
            second_tool_colour(at(inside)),
            "no tool at {inside:?}: {:?}",
            at(inside)
        );
        assert!(
            !second_tool_colour(at(outside)),
            "the tool reaches {outside:?}: {:?}",
            at(outside)
        );
    }
    let first = project(&mut browser, a);
    assert!(!second_tool_colour(at(first)), "{:?}", at(first));
    drop(browser);
    let run = view.stop().expect("stops").expect("a live run");
    assert_eq!(run.servo.devices(), 2);
}

/// The translucent violet of an effect's box over the dark background or the floor grid
/// (both grey: their green above their red).
fn zone_colour(px: [u8; 4]) -> bool {
    let [r, g, b, _] = px.map(i32::from);
    r > g && b > g + 15
}

#[test]
fn effect_zones_are_drawn_where_they_act() {
    let mut scene = sphere_scene();
    let (lo, hi, centre, radius) = sphere_bounds(&scene);
    // A viscous box beside the sphere, a viscosity inside the sphere (id 0), a spring
    // anchored above it, and a vibration, which has no place to draw.
    let min = DVec3::new(hi.x + 0.3 * radius, lo.y, lo.z);
    let max = DVec3::new(hi.x + 1.1 * radius, hi.y, hi.z);
    let anchor = DVec3::new(centre.x, centre.y, hi.z + 0.5 * radius);
    for effect in [
        Effect::viscosity(2.0, Zone::Box { min, max }),
        Effect::viscosity(5.0, Zone::Inside(ObjectId(0))),
        Effect::spring(10.0, anchor),
        Effect::vibration(150.0, 0.3),
    ] {
        scene
            .add_effect(effect.expect("a valid effect"))
            .expect("room for it");
    }
    let model = Model::from_scene(&scene, &["sphere".to_string()]);
    let start = DVec3::new(centre.x - radius, centre.y, hi.z + 0.6 * radius);
    let view = live_view(
        model,
        scene,
        start,
        (Vec::new(), None),
        false,
        "effects around a sphere",
        ServoOptions::default(),
    );
    let mut browser = Browser::start(WIDTH, HEIGHT);
    browser.navigate(&view.url());
    browser.wait_for(
        "!!(window.haphe && window.haphe.ready && window.haphe.frames > 2)",
        Duration::from_secs(40),
        "the page to draw and receive frames",
    );
    let effects = browser.eval("window.haphe.effects");
    let list = effects.as_array().expect("a list of effects");
    let kinds: Vec<(&str, &str)> = list
        .iter()
        .map(|e| {
            (
                e["effect"].as_str().expect("a kind"),
                e["kind"].as_str().expect("a place"),
            )
        })
        .collect();
    assert_eq!(
        kinds,
        [
            ("viscosity", "box"),
            ("viscosity", "object"),
            ("spring", "point"),
            ("vibration", "everywhere")
        ]
    );
    // The box drawn spans the zone (the page draws in f32).
    let corner = |v: &Value| DVec3::from_array([0, 1, 2].map(|k| v[k].as_f64().expect("a number")));
    let drawn = &list[0]["drawn"];
    for (at, zone) in [(corner(&drawn["min"]), min), (corner(&drawn["max"]), max)] {
        assert!(
            (at - zone).length() < 1e-6 * radius.max(1.0),
            "{at} vs {zone}"
        );
    }
    assert_eq!(list[1]["drawn"]["id"].as_u64(), Some(0));
    assert!((corner(&list[2]["drawn"]["at"]) - anchor).length() < 1e-6 * radius.max(1.0));
    assert!(list[3]["drawn"].is_null());
    // On the screen: the box's violet where its centre is, over the background.
    let (w, _, pixels) = decode_png(&browser.screenshot());
    let middle = project(&mut browser, 0.5 * (min + max));
    let px = pixels[(middle.1 as u32 * w + middle.0 as u32) as usize];
    assert!(zone_colour(px), "no zone at {middle:?}: {px:?}");
    let outside = project(
        &mut browser,
        DVec3::new(
            max.x + 0.5 * radius,
            0.5 * (min.y + max.y),
            max.z + 0.3 * radius,
        ),
    );
    let px = pixels[(outside.1 as u32 * w + outside.0 as u32) as usize];
    assert!(!zone_colour(px), "the zone reaches {outside:?}: {px:?}");
    let text = browser.eval("document.getElementById('effects').textContent");
    assert_eq!(
        text.as_str(),
        Some("viscosity in the box, viscosity inside sphere, spring to the marker, vibration")
    );
    view.stop().expect("stops");
    let errors = std::mem::take(&mut browser.errors);
    assert!(errors.is_empty(), "console errors: {errors:#?}");
}

/// A deforming object is redrawn from the vertices its deformer publishes: the page draws
/// the version it received last, each vertex where that version has it.
#[test]
fn a_deforming_object_is_redrawn_from_its_current_vertices() {
    let scene = sphere_scene();
    let (_, hi, centre, radius) = sphere_bounds(&scene);
    let rest: Vec<DVec3> = scene.objects()[0].shape.surface().vertices().to_vec();
    let (publisher, feed) = haphe_view::shape_channel();
    let model = Model::from_scene(&scene, &["sphere".to_string()]).with_shape_feed(feed);
    let start = DVec3::new(centre.x, centre.y, hi.z + 1.5 * radius);
    let view = live_view(
        model,
        scene,
        start,
        (Vec::new(), None),
        false,
        "a breathing sphere",
        ServoOptions::default(),
    );
    // Version k: the sphere scaled about its centre by 1 + 0.01 k, published at 100 Hz
    // (the page gets at most 30 a second) until the test is done.
    let scale = |k: u64| 1.0 + 0.01 * k as f64;
    let done = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let deformer = {
        let (done, rest) = (std::sync::Arc::clone(&done), rest.clone());
        std::thread::spawn(move || {
            let mut k = 1;
            while !done.load(std::sync::atomic::Ordering::Relaxed) && k < 3000 {
                let vertices: Vec<DVec3> = rest
                    .iter()
                    .map(|&p| centre + scale(k) * (p - centre))
                    .collect();
                publisher.publish_vertices(0, k, &vertices);
                k += 1;
                std::thread::sleep(Duration::from_millis(10));
            }
        })
    };
    let mut browser = Browser::start(WIDTH, HEIGHT);
    browser.navigate(&view.url());
    browser.wait_for(
        "!!(window.haphe && window.haphe.ready && window.haphe.shapes[0] && window.haphe.shapes[0].updates >= 3)",
        Duration::from_secs(40),
        "the page to redraw the sphere three times",
    );
    // Read at once: the version drawn and where three vertices are drawn.
    let seen = browser.eval(
        "JSON.stringify({ d: window.haphe.shapes[0], v: [0, 7, 100].map((i) => window.haphe.vertex(0, i)) })",
    );
    let seen: Value = serde_json::from_str(seen.as_str().expect("text")).expect("json");
    done.store(true, std::sync::atomic::Ordering::Relaxed);
    deformer.join().expect("the deformer");
    let version = seen["d"]["version"].as_u64().expect("a version");
    assert!(version >= 3, "{seen}");
    for (j, i) in [0usize, 7, 100].into_iter().enumerate() {
        let drawn = DVec3::from_array([0, 1, 2].map(|k| seen["v"][j][k].as_f64().expect("xyz")));
        let expected = centre + scale(version) * (rest[i] - centre);
        // The page draws in f32.
        assert!(
            (drawn - expected).length() < 1e-6,
            "vertex {i}: drawn at {drawn}, version {version} has it at {expected}"
        );
        assert!(
            (drawn - rest[i]).length() > 0.02 * radius,
            "vertex {i} did not move"
        );
    }
    view.stop().expect("stops");
    let errors = std::mem::take(&mut browser.errors);
    assert!(errors.is_empty(), "console errors: {errors:#?}");
}
