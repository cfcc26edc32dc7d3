//! Tests of the ink model and its file.

use std::path::Path;

use super::*;
use crate::deck::{InkFile, parse_deck};

fn line(tool: Tool, from: [f32; 2], to: [f32; 2]) -> Stroke {
    let mut b = StrokeBuilder::new(tool, 1, from);
    for i in 1..=100 {
        let t = i as f32 / 100.0;
        b.push([
            from[0] + t * (to[0] - from[0]),
            from[1] + t * (to[1] - from[1]),
        ]);
    }
    b.finish()
}

#[test]
fn add_undo_clear_per_slide() {
    let mut ink = Ink::default();
    ink.add("taylor", line(Tool::Pen, [0.0, 0.0], [100.0, 0.0]));
    ink.add(
        "taylor",
        line(Tool::Highlighter, [0.0, 50.0], [100.0, 50.0]),
    );
    ink.add("rk4", line(Tool::Pen, [10.0, 10.0], [20.0, 20.0]));
    assert_eq!(ink.strokes("taylor").len(), 2);
    assert_eq!(ink.stroke_count(), 3);
    // Undo takes the newest stroke of that slide only.
    let undone = ink.undo("taylor").unwrap();
    assert_eq!(undone.tool, Tool::Highlighter);
    assert_eq!(ink.strokes("taylor").len(), 1);
    assert_eq!(ink.strokes("rk4").len(), 1);
    assert_eq!(ink.clear("rk4"), 1);
    assert!(ink.strokes("rk4").is_empty());
    assert_eq!(ink.clear("rk4"), 0);
    assert!(ink.undo("taylor").is_some());
    assert!(ink.undo("taylor").is_none());
    assert!(ink.is_empty(), "no empty slide entries are left behind");
    // An empty stroke is never stored.
    ink.add(
        "x",
        Stroke {
            tool: Tool::Pen,
            color: 0,
            width: 6.0,
            points: vec![],
        },
    );
    assert!(ink.is_empty());
}

#[test]
fn ink_stays_with_its_slide_when_a_slide_is_inserted_before_it() {
    let deck = |extra: &str| {
        let text = format!(
            r#"(title: "D", slides: [{extra}
                (id: "euler", title: "Euler", body: []),
                (title: "Taylor", body: []),
            ])"#
        );
        parse_deck(&text, Path::new("d.ron")).unwrap()
    };
    let before = deck("");
    let mut ink = Ink::default();
    // Ink on the second slide, which has no id: its title is its key.
    ink.add(
        before.slides[1].key(),
        line(Tool::Pen, [1.0, 1.0], [9.0, 9.0]),
    );
    ink.add(
        before.slides[0].key(),
        line(Tool::Pen, [5.0, 1.0], [9.0, 9.0]),
    );
    let after = deck(r#"(id: "new", title: "Inserted", body: []),"#);
    assert!(ink.strokes(after.slides[0].key()).is_empty(), "new slide");
    assert_eq!(ink.strokes(after.slides[1].key()).len(), 1, "euler");
    assert_eq!(ink.strokes(after.slides[2].key()).len(), 1, "taylor");
    assert_eq!(
        ink.strokes(after.slides[2].key())[0].points[0],
        [1.0, 1.0],
        "taylor kept its own stroke"
    );
}

#[test]
fn canvas_units_do_not_depend_on_the_window() {
    // The same spot of a 16:9 slide in a 1280x720 window and letterboxed in a 2000x1500 one.
    let small = CanvasFrame {
        min_points: [0.0, 0.0],
        points_per_unit: 1280.0 / 1920.0,
    };
    let big = CanvasFrame {
        min_points: [0.0, (1500.0 - 1125.0) / 2.0],
        points_per_unit: 2000.0 / 1920.0,
    };
    let at_small = [640.0, 180.0]; // centre column, a quarter down
    let at_big = [1000.0, 187.5 + 1125.0 / 4.0];
    let a = small.canvas_from_screen(at_small);
    let b = big.canvas_from_screen(at_big);
    assert!(
        (a[0] - 960.0).abs() < 1e-3 && (a[1] - 270.0).abs() < 1e-3,
        "{a:?}"
    );
    assert!(
        (a[0] - b[0]).abs() < 1e-3 && (a[1] - b[1]).abs() < 1e-3,
        "{a:?} {b:?}"
    );
    let back = big.screen_from_canvas(b);
    assert!((back[0] - at_big[0]).abs() < 1e-3 && (back[1] - at_big[1]).abs() < 1e-3);
}

#[test]
fn thinning_keeps_the_shape_with_few_points() {
    // A circle of radius 100 units, sampled every 0.25 units (a fast mouse gives ~1-5).
    let mut b = StrokeBuilder::new(Tool::Pen, 0, [100.0, 0.0]);
    let n = 2513;
    for i in 1..=n {
        let a = i as f32 / n as f32 * std::f32::consts::TAU;
        b.push([100.0 * a.cos(), 100.0 * a.sin()]);
    }
    // While drawing: one point per 2 units of path at most (628 units of circle).
    let live = b.preview().points.len();
    assert!((250..=315).contains(&live), "{live} points while drawing");
    let s = b.finish();
    assert!(
        s.points.len() < 120 && s.points.len() > 20,
        "{} points kept for a 628-unit circle",
        s.points.len()
    );
    // Every kept point is on the circle, and no gap is wider than a pen stroke's curvature
    // allows: the polyline stays within 1 unit of the circle.
    for w in s.points.windows(2) {
        let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
        let r = mid[0].hypot(mid[1]);
        assert!((r - 100.0).abs() < 1.0, "chord midpoint at r = {r}");
    }
    for p in &s.points {
        assert!((p[0].hypot(p[1]) - 100.0).abs() < 0.2);
    }
    // The end point is kept even when it is closer than the step to the last kept point.
    let mut b = StrokeBuilder::new(Tool::Pen, 0, [0.0, 0.0]);
    b.push([10.0, 0.0]);
    b.push([11.0, 0.0]);
    assert_eq!(b.finish().points.last(), Some(&[11.0, 0.0]));
    // A click is a dot.
    let dot = StrokeBuilder::new(Tool::Pen, 0, [3.0, 4.0]).finish();
    assert_eq!(dot.points, vec![[3.0, 4.0]]);
}

#[test]
fn simplify_drops_only_points_on_straight_runs() {
    let pts: Vec<[f32; 2]> = (0..=10).map(|i| [i as f32, 0.0]).collect();
    assert_eq!(simplify(&pts, 0.5), vec![[0.0, 0.0], [10.0, 0.0]]);
    let corner = vec![[0.0, 0.0], [5.0, 0.0], [5.0, 5.0]];
    assert_eq!(simplify(&corner, 0.5), corner);
}

#[test]
fn file_round_trip_and_reload_from_disk() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("talk.ron");
    assert_eq!(ink_file_path(&deck), dir.path().join("talk.ink.ron"));
    let mut file = InkFile::for_deck(&deck);
    assert!(
        file.ink().is_empty() && file.problem().is_none(),
        "no file, no ink, no error"
    );
    let circle = line(Tool::Pen, [100.5, 200.25], [300.0, 400.0]);
    file.add("taylor", circle.clone()).unwrap();
    file.add("taylor", line(Tool::Highlighter, [0.0, 0.0], [1.0, 1.0]))
        .unwrap();
    let text = std::fs::read_to_string(ink_file_path(&deck)).unwrap();
    assert_eq!(Ink::parse(&text, Path::new("x")).unwrap(), *file.ink());
    let again = InkFile::for_deck(&deck);
    assert_eq!(again.ink(), file.ink());
    assert_eq!(again.ink().strokes("taylor")[0], circle);

    // Our own write is not a reload; another program's is.
    let path = ink_file_path(&deck);
    assert!(!file.on_changes(std::slice::from_ref(&path)));
    let mut other = Ink::default();
    other.add("rk4", line(Tool::Pen, [0.0, 0.0], [50.0, 0.0]));
    std::fs::write(&path, other.to_ron()).unwrap();
    assert!(file.on_changes(std::slice::from_ref(&path)));
    assert_eq!(*file.ink(), other);
    // No temp file left beside the deck.
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 1, "{names:?}");
}

#[test]
fn damaged_ink_files_are_reported_and_ignored() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("talk.ron");
    let path = ink_file_path(&deck);
    let mut good = Ink::default();
    good.add("a", line(Tool::Pen, [0.0, 0.0], [50.0, 0.0]));
    let full = good.to_ron();
    let cases = [
        ("half-written", full[..full.len() / 2].to_owned()),
        ("garbage", "\u{1}\u{2}not ink at all {{{".to_owned()),
        ("not finite", full.replacen("(0.0, 0.0)", "(NaN, 0.0)", 1)),
        ("colour", full.replacen("color: 1", "color: 9", 1)),
    ];
    for (what, text) in &cases {
        assert_ne!(text, &full, "{what}: the case must damage the file");
        std::fs::write(&path, text).unwrap();
        let file = InkFile::for_deck(&deck);
        assert!(file.ink().is_empty(), "{what}: ignored");
        let p = file.problem().unwrap_or_else(|| panic!("{what}: reported"));
        assert!(p.to_string().contains("talk.ink.ron"), "{what}: {p}");
    }
    // A damaged file that appears while presenting keeps the ink on screen.
    std::fs::write(&path, &full).unwrap();
    let mut file = InkFile::for_deck(&deck);
    assert_eq!(*file.ink(), good);
    std::fs::write(&path, &full[..full.len() / 3]).unwrap();
    assert!(!file.on_changes(std::slice::from_ref(&path)));
    assert_eq!(*file.ink(), good, "last good ink stays");
    assert!(file.problem().is_some());
    // The next stroke keeps the damaged file aside and writes the good ink.
    file.add("b", line(Tool::Pen, [0.0, 0.0], [9.0, 9.0]))
        .unwrap();
    assert!(file.problem().is_none());
    let aside = dir.path().join("talk.ink.ron.damaged");
    assert_eq!(
        std::fs::read_to_string(aside).unwrap(),
        &full[..full.len() / 3]
    );
    assert_eq!(InkFile::for_deck(&deck).ink().stroke_count(), 2);
}
