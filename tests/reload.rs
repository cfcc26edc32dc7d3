//! Hot reload of a deck, driven through the real folder watcher and the same `DeckSession` the
//! app uses, with files written the ways editors write them.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use lectern::deck::DeckSession;
use lectern::reload::{DEBOUNCE, Reloaded};

fn deck_text(titles: &[&str]) -> String {
    let slides: Vec<String> = titles
        .iter()
        .map(|t| format!("    (id: \"{t}\", title: \"{t}\"),"))
        .collect();
    format!(
        "// a deck\n(\n  title: \"reload test\",\n  slides: [\n{}\n  ],\n)\n",
        slides.join("\n")
    )
}

fn titles(s: &DeckSession) -> Vec<String> {
    s.deck().slides.iter().map(|s| s.title.clone()).collect()
}

/// A session on a fresh deck in a temporary folder, watching it.
fn session(initial: &[&str]) -> (tempfile::TempDir, PathBuf, DeckSession) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("talk.ron");
    std::fs::write(&path, deck_text(initial)).unwrap();
    let mut s = DeckSession::open(&path).unwrap();
    s.watch(DEBOUNCE, || {}).unwrap();
    // inotify watches are in place once `watch` returns; a short pause lets the debouncer's
    // thread start so the first event is not raced.
    std::thread::sleep(Duration::from_millis(50));
    (dir, path, s)
}

/// Pumps the watcher until `done` holds or 10 s pass (the debounce is 50 ms; CI machines are
/// slow and shared).
fn wait_until(s: &mut DeckSession, mut done: impl FnMut(&DeckSession) -> bool) -> bool {
    let deadline = Instant::now() + Duration::from_secs(10);
    while Instant::now() < deadline {
        if done(s) {
            return true;
        }
        s.wait(Duration::from_millis(200));
    }
    done(s)
}

/// vim with `backupcopy=no`: write a new file, rename it over the deck.
fn save_like_vim(path: &Path, text: &str) {
    let tmp = path.with_file_name("4913");
    std::fs::write(&tmp, "").unwrap();
    std::fs::remove_file(&tmp).unwrap();
    let swap = path.with_file_name(".talk.ron.swp");
    std::fs::write(&swap, "swap").unwrap();
    let new = path.with_extension("ron.new");
    std::fs::write(&new, text).unwrap();
    std::fs::rename(&new, path).unwrap();
    std::fs::remove_file(&swap).unwrap();
}

/// VS Code: truncate the file, then write the new content into it (in two chunks, as a slow
/// writer would).
fn save_like_vscode(path: &Path, text: &str) {
    let mut f = std::fs::OpenOptions::new()
        .write(true)
        .truncate(true)
        .open(path)
        .unwrap();
    f.flush().unwrap();
    let (a, b) = text.split_at(text.len() / 2);
    f.write_all(a.as_bytes()).unwrap();
    f.flush().unwrap();
    f.write_all(b.as_bytes()).unwrap();
    f.sync_all().unwrap();
}

#[test]
fn save_by_rename_like_vim_is_picked_up_again_and_again() {
    let (_dir, path, mut s) = session(&["a", "b"]);
    // Twice: a per-file watch would die after the first rename; the folder watch must not.
    for round in ["c", "d"] {
        save_like_vim(&path, &deck_text(&["a", "b", round]));
        assert!(
            wait_until(&mut s, |s| titles(s).last().map(String::as_str)
                == Some(round)),
            "after a vim-style save the deck should end with {round}: {:?}",
            titles(&s)
        );
        assert!(s.error().is_none(), "{:?}", s.error());
    }
}

#[test]
fn truncate_and_write_like_vscode() {
    let (_dir, path, mut s) = session(&["a"]);
    save_like_vscode(&path, &deck_text(&["a", "vscode"]));
    assert!(
        wait_until(&mut s, |s| titles(s) == ["a", "vscode"]
            && s.error().is_none()),
        "{:?} {:?}",
        titles(&s),
        s.error()
    );
}

#[test]
fn an_empty_file_mid_save_is_not_acted_on() {
    let (_dir, path, mut s) = session(&["a"]);
    std::fs::write(&path, "").unwrap();
    let outcome = s.apply_changed(std::slice::from_ref(&path));
    assert_eq!(outcome, Some(Reloaded::Waiting));
    assert_eq!(titles(&s), ["a"]);
    assert!(s.error().is_none(), "an empty file is not an error");
}

#[test]
fn burst_of_100_saves_ends_on_the_final_content() {
    let (_dir, path, mut s) = session(&["start"]);
    for i in 0..100 {
        let last = format!("save-{i}");
        let text = deck_text(&["start", &last]);
        if i % 2 == 0 {
            save_like_vim(&path, &text);
        } else {
            save_like_vscode(&path, &text);
        }
    }
    assert!(
        wait_until(&mut s, |s| titles(s) == ["start", "save-99"]),
        "held {:?}, error {:?}",
        titles(&s),
        s.error()
    );
    // Settled: nothing more arrives, and the held deck is exactly the file.
    s.wait(Duration::from_millis(300));
    assert_eq!(titles(&s), ["start", "save-99"]);
    assert!(s.error().is_none(), "{:?}", s.error());
}

#[test]
fn broken_save_keeps_the_old_deck_with_an_error_until_fixed() {
    let (_dir, path, mut s) = session(&["a", "b", "c"]);
    s.navigate(|nav, deck| nav.go(deck, 2));
    // line 5 holds the first slide; break its closing parenthesis
    let broken = deck_text(&["a", "b", "c"]).replacen("title: \"a\"),", "title: \"a\",,", 1);
    save_like_vscode(&path, &broken);
    assert!(
        wait_until(&mut s, |s| s.error().is_some()),
        "no error reported"
    );
    let err = s.error().unwrap().clone();
    assert_eq!(titles(&s), ["a", "b", "c"], "the last good deck stays");
    assert_eq!(s.nav().index(), 2, "the presenter stays on the slide");
    assert!(err.file.ends_with("talk.ron"), "{err}");
    assert_eq!(err.line, 5, "{err}");
    assert!(err.col > 0, "{err}");

    // Fixed, with a slide inserted before the current one: the notice goes, the place is kept.
    save_like_vim(&path, &deck_text(&["a", "new", "b", "c"]));
    assert!(
        wait_until(&mut s, |s| s.error().is_none()),
        "{:?}",
        s.error()
    );
    assert_eq!(titles(&s), ["a", "new", "b", "c"]);
    assert_eq!(s.nav().index(), 3, "still on slide c");
}

#[test]
fn deleting_the_deck_keeps_the_last_good_version() {
    let (_dir, path, mut s) = session(&["a"]);
    std::fs::remove_file(&path).unwrap();
    assert!(wait_until(&mut s, |s| s.error().is_some()));
    assert_eq!(titles(&s), ["a"]);
    std::fs::write(&path, deck_text(&["back"])).unwrap();
    assert!(wait_until(&mut s, |s| titles(s) == ["back"] && s.error().is_none()));
}

#[test]
fn garbage_bytes_and_other_files_never_crash() {
    let (dir, path, mut s) = session(&["a"]);
    std::fs::write(&path, [0xff, 0xfe, 0x00, 0x41]).unwrap();
    std::fs::write(dir.path().join("notes.txt"), "unrelated").unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(dir.path().join("sub/x.ron"), "(").unwrap();
    s.wait(Duration::from_millis(400));
    assert_eq!(titles(&s), ["a"]);
    std::fs::write(&path, deck_text(&["ok"])).unwrap();
    assert!(wait_until(&mut s, |s| titles(s) == ["ok"]));
}
