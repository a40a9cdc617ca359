//! The browser viewer (`viewer/`), tested in a real browser: Debian's headless Chromium,
//! driven by `tests/viewer/viewer_test.js` (playwright-core, installed by `.ci/setup` with
//! `npm ci`). This test builds recordings — the C examples run with a recording path, a mixed
//! scene recorded through the Rust recorder, a truncated copy — decodes them with the Rust
//! reader, writes what must be seen at a few frames into a JSON file, and runs the script:
//! the page loads each recording (file picker, or `?file=` from a loopback server), is not
//! blank, shows each checked body's colour where the page's camera projects its recorded
//! position after scrubbing to the frame, and names the body when it is clicked.
//! Screenshots are kept under `target/viewer-screenshots/` (paths printed).

mod common;

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;

use common::{compiler, link, root, run, Link};
use hearth::joints::BallParams;
use hearth::particles::ParticleDef;
use hearth::record::format::{BODY_DYNAMIC, BODY_KINEMATIC};
use hearth::record::read::{self, ShapeRecord};
use hearth::record::{RecordOptions, Recorder};
use hearth::soft::{mesh, SoftBodyDef};
use hearth::{BodyDef, BodyType, Geometry, JointDef, JointKind, Quat, ShapeDef, Transform, Vec3};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

fn out_dir() -> PathBuf {
    common::out_dir("viewer")
}

fn chromium() -> PathBuf {
    let p = PathBuf::from(std::env::var("HEARTH_CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into()));
    assert!(
        p.exists(),
        "{} not found: `bash .ci/setup` installs Debian's chromium (or set HEARTH_CHROMIUM)",
        p.display()
    );
    p
}

/// Builds `examples/c/<name>.c` and runs it with a recording path; returns the recording.
fn record_c_example(name: &str) -> PathBuf {
    let exe = out_dir().join(format!("{name}_example"));
    let mut cmd = compiler(false, &out_dir());
    cmd.arg(root().join("examples/c").join(format!("{name}.c")))
        .arg("-o")
        .arg(&exe);
    link(&mut cmd, Link::Shared);
    run(&mut cmd);
    let recording = out_dir().join(format!("{name}.hrec"));
    let _ = std::fs::remove_file(&recording);
    run(common::program(&exe).arg(&recording).current_dir(out_dir()));
    recording
}

/// A scene with every kind of thing the viewer draws, with user data on its bodies: ground
/// plane, kinematic box, spheres, boxes and capsules, a ball joint, particles, a soft ball.
fn record_mixed_scene() -> PathBuf {
    let mut w = scenes::world(true);
    scenes::ground_plane(&mut w);
    let kin = w
        .create_body(&BodyDef {
            body_type: BodyType::Kinematic,
            transform: Transform::new(Vec3::new(3.0, 0.5, 2.0), Quat::IDENTITY),
            angular_velocity: Vec3::new(0.0, 1.0, 0.0),
            user_data: 9,
            ..Default::default()
        })
        .unwrap();
    let slab = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::new(1.0, 0.2, 1.0),
    };
    w.create_shape(kin, &ShapeDef::default(), &slab).unwrap();
    let mut first = None;
    for i in 0..9u64 {
        let b = w
            .create_body(&BodyDef {
                body_type: BodyType::Dynamic,
                transform: Transform::new(
                    Vec3::new(
                        (i % 3) as f32 * 1.6 - 1.6,
                        1.0 + (i / 3) as f32 * 1.3,
                        (i / 3) as f32 * 0.4,
                    ),
                    Quat::from_rotation_z(0.2 * i as f32),
                ),
                user_data: 5000 + i,
                ..Default::default()
            })
            .unwrap();
        let g = match i % 3 {
            0 => Geometry::Sphere {
                center: Vec3::ZERO,
                radius: 0.45,
            },
            1 => Geometry::Box {
                center: Vec3::ZERO,
                rotation: Quat::IDENTITY,
                half_extents: Vec3::splat(0.4),
            },
            _ => Geometry::Capsule {
                a: Vec3::new(-0.35, 0.0, 0.0),
                b: Vec3::new(0.35, 0.0, 0.0),
                radius: 0.3,
            },
        };
        w.create_shape(b, &ShapeDef::default(), &g).unwrap();
        first.get_or_insert(b);
    }
    let mut ball = JointDef::new(JointKind::Ball(BallParams::default()));
    ball.body_a = first.unwrap();
    ball.frame_a = Transform::new(Vec3::new(0.0, 0.45, 0.0), Quat::IDENTITY);
    ball.frame_b = Transform::new(Vec3::new(-1.6, 3.5, 0.0), Quat::IDENTITY);
    w.create_joint(&ball).unwrap();
    for i in 0..40 {
        w.create_particle(&ParticleDef {
            position: Vec3::new(-3.0 + 0.15 * i as f32, 5.0, -2.0),
            velocity: Vec3::new(0.0, 2.0, 0.5),
            radius: 0.06,
            ..Default::default()
        })
        .unwrap();
    }
    let soft = SoftBodyDef {
        transform: Transform::new(Vec3::new(0.0, 4.5, -2.5), Quat::IDENTITY),
        pressure: 200.0,
        ..Default::default()
    };
    w.create_soft_body(&soft, &mesh::icosphere(0.7, 2), None).unwrap();
    let mut rec = Recorder::new(&w, RecordOptions { contacts: true });
    let mut bytes = rec.bytes().to_vec();
    rec.clear();
    for _ in 0..120 {
        let t = std::time::Instant::now();
        w.step(1.0 / 60.0).unwrap();
        rec.record_step(&w, 1.0 / 60.0, t.elapsed().as_secs_f32());
        bytes.extend_from_slice(rec.bytes());
        rec.clear();
    }
    let path = out_dir().join("mixed.hrec");
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Smallest half-size of a shape: how far from its centre the body surely covers.
fn extent(shape: &ShapeRecord) -> f32 {
    match *shape {
        ShapeRecord::Sphere { radius, .. } | ShapeRecord::Capsule { radius, .. } => radius,
        ShapeRecord::Box { half_extents, .. } => half_extents.min_element(),
        ShapeRecord::Plane { .. } => 0.0,
    }
}

/// The JSON description of a case: frame count, and per checked frame every awake dynamic
/// or kinematic body whose origin lies inside its one shape, as the Rust reader decodes it.
fn case_json(
    name: &str,
    file: &Path,
    via: &str,
    frames_to_check: &[usize],
    screenshot: Option<(usize, &Path)>,
) -> String {
    let bytes = std::fs::read(file).unwrap();
    let r = read::parse(&bytes).unwrap();
    let mut checks = Vec::new();
    for &f in frames_to_check {
        assert!(f < r.frames.len(), "{name}: frame {f} of {}", r.frames.len());
        let mut bodies = Vec::new();
        for (index, s) in r.bodies_at(f) {
            let rec = match s.record {
                Some(rec) if rec.awake => rec,
                _ => continue,
            };
            // Only dynamic bodies: kinematic ones are paler; one centred shape each.
            if s.def.body_type != BODY_DYNAMIC || s.def.shapes.len() != 1 {
                continue;
            }
            let centred = match s.def.shapes[0] {
                ShapeRecord::Sphere { center, .. } | ShapeRecord::Box { center, .. } => center == Vec3::ZERO,
                ShapeRecord::Capsule { a, b, .. } => a + b == Vec3::ZERO,
                ShapeRecord::Plane { .. } => false,
            };
            if !centred {
                continue;
            }
            let v = rec.linear_velocity;
            let speed = ((v.x as f64).powi(2) + (v.y as f64).powi(2) + (v.z as f64).powi(2)).sqrt();
            let p = rec.pose.p;
            bodies.push(format!(
                "{{\"index\":{index},\"generation\":{},\"userData\":\"{}\",\"awake\":true,\"speed\":{speed},\"extent\":{},\"position\":[{},{},{}]}}",
                s.def.generation,
                s.def.user_data,
                extent(&s.def.shapes[0]),
                p.x,
                p.y,
                p.z
            ));
        }
        assert!(!bodies.is_empty(), "{name}: no awake dynamic body at frame {f}");
        checks.push(format!("{{\"frame\":{f},\"bodies\":[{}]}}", bodies.join(",")));
    }
    let mut s = format!(
        "{{\"name\":\"{name}\",\"file\":{:?},\"via\":\"{via}\",\"frames\":{},\"truncated\":{},\"checks\":[{}]",
        file.display().to_string(),
        r.frames.len(),
        r.truncated,
        checks.join(",")
    );
    if let Some((frame, path)) = screenshot {
        write!(
            s,
            ",\"screenshot\":{{\"frame\":{frame},\"path\":{:?}}}",
            path.display().to_string()
        )
        .unwrap();
    }
    s.push('}');
    s
}

#[test]
fn the_viewer_replays_recordings_in_headless_chromium() {
    let chromium = chromium();
    let script_dir = root().join("tests").join("viewer");
    assert!(
        script_dir.join("node_modules").join("playwright-core").exists(),
        "tests/viewer/node_modules is missing: `bash .ci/setup` runs `npm ci` there"
    );
    let pyramid = record_c_example("pyramid");
    let chain = record_c_example("chain_door");
    let mixed = record_mixed_scene();
    // A copy of the pyramid cut in the middle of a chunk, as a crash would leave it.
    let bytes = std::fs::read(&pyramid).unwrap();
    let truncated = out_dir().join("pyramid_truncated.hrec");
    std::fs::write(&truncated, &bytes[..bytes.len() * 2 / 3 + 7]).unwrap();
    let whole = read::parse(&bytes).unwrap().frames.len();
    let cut = read::parse(&bytes[..bytes.len() * 2 / 3 + 7]).unwrap();
    assert!(cut.truncated && cut.frames.len() < whole && cut.frames.len() > 100);

    let shots = root().join("target").join("viewer-screenshots");
    std::fs::create_dir_all(&shots).unwrap();
    let kinds = [BODY_KINEMATIC]; // referenced so the mixed scene's kinematic body stays documented
    assert_eq!(kinds.len(), 1);
    let cases = [
        case_json(
            "pyramid",
            &pyramid,
            "picker",
            &[40, 150],
            Some((75, &shots.join("pyramid_overview.png"))),
        ),
        case_json("chain_door", &chain, "url", &[120], None),
        case_json(
            "mixed",
            &mixed,
            "picker",
            &[20, 90],
            Some((45, &shots.join("mixed_overview.png"))),
        ),
        case_json("pyramid_truncated", &truncated, "url", &[60], None),
    ];
    let config = format!(
        "{{\"chromium\":{:?},\"viewerDir\":{:?},\"serveRoot\":{:?},\"outDir\":{:?},\"cases\":[{}]}}",
        chromium.display().to_string(),
        root().join("viewer").display().to_string(),
        // The loopback server serves the repository's viewer/ and the recordings under target/.
        root().display().to_string(),
        shots.display().to_string(),
        cases.join(",")
    );
    let config_path = out_dir().join("viewer_test.json");
    std::fs::write(&config_path, config).unwrap();
    let started = std::time::Instant::now();
    let out = Command::new("node")
        .arg(script_dir.join("viewer_test.js"))
        .arg(&config_path)
        .current_dir(&script_dir)
        .output()
        .expect("cannot run node (is Node.js installed?)");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    println!("{text}");
    println!("viewer test: {:.1} s", started.elapsed().as_secs_f64());
    assert!(
        out.status.success() && text.contains(" 0 failed"),
        "the viewer test failed:\n{text}"
    );
}
