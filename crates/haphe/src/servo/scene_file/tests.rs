//! Parsing and checking scene files.

use super::*;

fn err(text: &str) -> String {
    parse_scene(Path::new("dir/s.toml"), text)
        .err()
        .map(|e| e.message)
        .unwrap_or_default()
}

#[test]
fn objects_are_read_with_their_sources_poses_and_motions() {
    let text = "[[object]]\nshape = \"box\"\ntriangles = 500\n\n[[object]]\nname = \"part\"\n\
                id = 7\nmesh = \"p.stl\"\nunits = \"mm\"\nposition = [1.0, 2.0, 3.0]\n\
                motion = { kind = \"linear\", velocity = [0.1, 0.0, 0.0] }\n";
    let entries = parse_scene(Path::new("dir/s.toml"), text).unwrap();
    assert_eq!(entries.len(), 2);
    assert_eq!(
        entries[0].source,
        ObjectSource::Shape {
            which: Catalog::Box,
            triangles: 500
        }
    );
    assert_eq!(
        (entries[0].id, entries[0].name.as_str()),
        (ObjectId(0), "box")
    );
    assert_eq!(
        entries[1].source,
        ObjectSource::Mesh {
            path: Path::new("dir/p.stl").to_path_buf(),
            units: Units::Millimetres
        }
    );
    assert_eq!(
        (entries[1].id, entries[1].name.as_str()),
        (ObjectId(7), "part")
    );
    assert_eq!(entries[1].pose.translation(), DVec3::new(1.0, 2.0, 3.0));
    let motion = entries[1].motion.as_ref().unwrap();
    assert_eq!(motion.id, ObjectId(7));
    assert!(matches!(motion.motion, Motion::Linear { velocity } if velocity.x == 0.1));
    assert_eq!(entries[1].place, "dir/s.toml: object 2 (line 5)");
}

#[test]
fn errors_name_the_file_the_object_and_the_line() {
    assert_eq!(err(""), "dir/s.toml: no [[object]] in the scene");
    assert!(err("[[object]]\nshape = \"box\"\ncolour = 1\n").starts_with("dir/s.toml: line 3:"));
    for (text, says) in [
        ("[[object]]\nshape = \"teapot\"\n", "shape \"teapot\""),
        ("[[object]]\n", "give `shape"),
        (
            "[[object]]\nshape = \"box\"\nmesh = \"a.stl\"\n",
            "not both",
        ),
        ("[[object]]\nshape = \"box\"\ntriangles = 0\n", "triangles"),
        (
            "[[object]]\nmesh = \"a.stl\"\nunits = \"furlong\"\n",
            "units \"furlong\"",
        ),
        (
            "[[object]]\nshape = \"box\"\nposition = [nan, 0.0, 0.0]\n",
            "`position` must be finite",
        ),
        (
            "[[object]]\nshape = \"box\"\nmaterial = { stiffness = -1.0 }\n",
            "material stiffness",
        ),
        (
            "[[object]]\nshape = \"box\"\nmotion = { kind = \"rotating\", axis = [0.0, 0.0, 0.0], rate = 1.0 }\n",
            "axis",
        ),
    ] {
        let e = err(text);
        assert!(
            e.starts_with("dir/s.toml: object 1 (line 1): "),
            "{text}: {e}"
        );
        assert!(e.contains(says), "{text}: {e}");
    }
    let twice = "[[object]]\nshape = \"box\"\nid = 3\n[[object]]\nshape = \"box\"\nid = 3\n";
    assert_eq!(
        err(twice),
        "dir/s.toml: object 2 (line 4): id 3 is used by another object"
    );
}

#[test]
fn a_grid_repeats_an_object_with_consecutive_ids() {
    let text = "[[object]]\nshape = \"sphere\"\ntriangles = 500\nid = 10\nposition = [1.0, 0.0, 0.0]\n\
                grid = { count = [3, 2, 1], spacing = [0.5, 0.25, 1.0] }\n\n\
                [[object]]\nshape = \"box\"\n";
    let entries = parse_scene(Path::new("dir/s.toml"), text).unwrap();
    assert_eq!(entries.len(), 7);
    assert_eq!(entries[4].id, ObjectId(14));
    assert_eq!(entries[4].name, "sphere[1,1,0]");
    assert_eq!(entries[4].pose.translation(), DVec3::new(1.5, 0.25, 0.0));
    // The object after the grid counts the copies before it.
    assert_eq!(entries[6].id, ObjectId(6));
    let clash = "[[object]]\nshape = \"box\"\nid = 2\n\n[[object]]\nshape = \"box\"\n\
                 grid = { count = [3, 1, 1], spacing = [1.0, 1.0, 1.0] }\n";
    assert!(
        err(clash).contains("id 2 is used by another object"),
        "{}",
        err(clash)
    );
}

#[test]
fn the_tool_radius_is_read_and_checked_naming_its_line() {
    let spec = |text: &str| parse_scene_spec(Path::new("dir/s.toml"), text);
    let object = "[[object]]\nshape = \"box\"\n";
    // Absent: none (the front end's default, a point, applies).
    assert!(spec(object).unwrap().tool_radius.is_none());
    // An integer is a number of metres too.
    for (given, metres) in [("0.002", 0.002), ("0", 0.0), ("5e-4", 5e-4)] {
        let text = format!("# the tool\ntool_radius = {given}\n\n{object}");
        let read = spec(&text).unwrap();
        assert_eq!(
            read.tool_radius,
            Some((metres, "dir/s.toml: line 2: tool_radius".to_string()))
        );
        assert_eq!(read.objects.len(), 1);
    }
    for (given, says) in [
        ("-0.001", "not -0.001"),
        ("nan", "not NaN"),
        ("inf", "not inf"),
        ("0.6", "not 0.6"),
    ] {
        let message = err(&format!("tool_radius = {given}\n{object}"));
        assert!(
            message.starts_with("dir/s.toml: line 1: tool_radius must be a finite number"),
            "{message}"
        );
        assert!(message.contains("0.5 m"), "{message}");
        assert!(message.ends_with(says), "{message}");
    }
    // Not a number; and written inside an object, where TOML puts a key after a header.
    assert!(err(&format!("tool_radius = \"2 mm\"\n{object}")).starts_with("dir/s.toml: line 1:"));
    let inside = err(&format!("{object}tool_radius = 0.002\n"));
    assert!(inside.starts_with("dir/s.toml: line 3:"), "{inside}");
    assert!(inside.contains("before the first [[object]]"), "{inside}");
}

#[test]
fn textures_and_effects_are_read_as_their_specifications_are() {
    let text = "# how it feels\neffects = [\n  \"viscosity:2\",\n  \"spring:100:0:0:0.1\",\n  \"viscosity:1:inside:4\",\n]\n\n\
                [[object]]\nshape = \"box\"\nid = 4\ntexture = \"sine:0.0002:0.002\"\n\
                grid = { count = [2, 1, 1], spacing = [1.0, 1.0, 1.0] }\n\n[[object]]\nshape = \"sphere\"\n";
    let spec = parse_scene_spec(Path::new("dir/s.toml"), text).unwrap();
    let texture: Texture = "sine:0.0002:0.002".parse().unwrap();
    // Both copies of the grid have the texture; the object without one has none.
    let textures: Vec<Option<&Texture>> = spec.objects.iter().map(|o| o.texture.as_ref()).collect();
    assert_eq!(textures, [Some(&texture), Some(&texture), None]);
    let effects: Vec<(&str, &str)> = spec
        .effects
        .iter()
        .map(|e| (e.spec.as_str(), e.place.as_str()))
        .collect();
    assert_eq!(
        effects,
        [
            ("viscosity:2", "dir/s.toml: line 3: effect"),
            ("spring:100:0:0:0.1", "dir/s.toml: line 4: effect"),
            ("viscosity:1:inside:4", "dir/s.toml: line 5: effect"),
        ]
    );
    for e in &spec.effects {
        assert_eq!(Ok(e.effect), e.spec.parse::<crate::scene::Effect>());
    }
    // No key: no texture, no effect.
    let plain = parse_scene_spec(Path::new("dir/s.toml"), "[[object]]\nshape = \"box\"\n").unwrap();
    assert!(plain.effects.is_empty() && plain.objects[0].texture.is_none());
}

#[test]
fn bad_textures_and_effects_name_the_file_and_the_line() {
    let object = "[[object]]\nshape = \"box\"\nid = 3\n";
    // A texture: the line of its key.
    for (texture, says) in [
        ("bumps:1:2", "unknown kind `bumps`"),
        ("sine:-0.001:0.01", "texture amplitude must be"),
        ("sine:nan:0.01", "texture amplitude must be"),
        ("sine:0.001:inf", "texture wavelength must be"),
        ("sine:0.001", "expected `KIND:AMPLITUDE:WAVELENGTH`"),
    ] {
        let e = err(&format!("{object}\ntexture = \"{texture}\"\n"));
        assert!(
            e.starts_with(&format!("dir/s.toml: line 5: texture `{texture}`: ")),
            "{e}"
        );
        assert!(e.contains(says), "{e}");
    }
    // An effect: the line of its element.
    for (effect, says) in [
        ("wobble:1", "unknown kind `wobble`"),
        ("viscosity:-2", "viscosity must be"),
        ("constant:0:0:nan", "effect force must be finite"),
        ("vibration:-150:0.3", "vibration frequency must be"),
        ("viscosity:2:inside:9", "no object of the file has id 9"),
        ("viscosity:2:box:1:0:0:0:1:1", "position must be"),
    ] {
        let e = err(&format!(
            "effects = [\n  \"viscosity:1\",\n  \"{effect}\",\n]\n{object}"
        ));
        assert!(
            e.starts_with(&format!("dir/s.toml: line 3: effect `{effect}`: ")),
            "{e}"
        );
        assert!(e.contains(says), "{e}");
    }
    // Not a list of text; too many; written inside an object.
    assert!(
        err(&format!("effects = \"viscosity:2\"\n{object}")).starts_with("dir/s.toml: line 1:")
    );
    let many = vec!["\"viscosity:1\""; crate::scene::MAX_EFFECTS + 1].join(",\n");
    let e = err(&format!("effects = [\n{many}]\n{object}"));
    assert!(
        e.starts_with(&format!(
            "dir/s.toml: line {}: effects: 17 effects, more than the limit of 16",
            crate::scene::MAX_EFFECTS + 2
        )),
        "{e}"
    );
    let inside = err(&format!("{object}effects = [\"viscosity:2\"]\n"));
    assert!(inside.starts_with("dir/s.toml: line 4:"), "{inside}");
    assert!(inside.contains("before the first [[object]]"), "{inside}");
}
