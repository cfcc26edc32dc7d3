//! Keys → actions, as a pure function of egui's input events, so the key map is testable and
//! the keys the app handles can be taken out of the input before slide widgets see them (a
//! focused slider must not eat the clicker's PageDown).

use egui::{Event, Key, Modifiers};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    Next,
    Prev,
    First,
    Last,
    /// `G`: start typing a slide number.
    GotoStart,
    GotoDigit(u8),
    GotoBackspace,
    GotoConfirm,
    ToggleOverview,
    ToggleFullscreen,
    ToggleBlack,
    /// `Tab`: slide mode ↔ scene mode.
    ToggleMode,
    ToggleHelp,
    /// `N`: the speaker notes under the slide (self-study, and the web player).
    ToggleNotes,
    /// Leaves overlays, then fullscreen.
    Escape,
    /// `P`: presenter overlay on a single screen.
    TogglePresenter,
    /// `C`: show the live-tweak controls on the audience screen.
    ToggleControls,
    /// `R`: reset the current slide's tweaks to the file's values.
    ResetTweaks,
    /// `Ctrl+1…9`: store the current slide's tweaks.
    BookmarkStore(u8),
    /// `1…9`: recall a stored tweak state.
    BookmarkRecall(u8),
    /// `Space` is taken by "next"; `T` pauses/resumes the talk timer.
    TimerPause,
    /// `Shift+T`: timer back to zero.
    TimerReset,
    /// `E`: export the current slide, as shown, to PNG.
    ExportSlide,
    /// `Ctrl+S`: write the current tweaks back into the deck file.
    WriteBack,
    /// `D`: the pen on / off (drawing on the slide).
    TogglePen,
    /// `H`: the highlighter on / off.
    ToggleHighlighter,
    /// `L`: the laser pointer on / off.
    ToggleLaser,
    /// `1…5` while drawing: ink colour slot 0…4 of the theme.
    InkColor(u8),
    /// `Ctrl+Z`: remove this slide's newest stroke.
    UndoInk,
    /// `Shift+D`: remove all ink on this slide.
    ClearInk,
    /// `Ctrl+Q`: close the window (also while typing in a field). A bare `Q` does not: one
    /// stray key must not end a lecture.
    Quit,
}

/// What the keys mean right now: digits go to the slide number while typing one after `G`,
/// to the ink colour while drawing, else to bookmarks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyMode {
    Normal,
    TypingNumber,
    Drawing,
}

/// One line per key for the `?` overlay: (keys, what they do).
pub const HELP: &[(&str, &str)] = &[
    ("→ ↓ Space PageDown click", "next slide"),
    ("← ↑ PageUp", "previous slide"),
    ("Home End", "first / last slide"),
    ("G number Enter", "go to slide"),
    ("O", "overview of all slides"),
    ("F F11", "fullscreen"),
    ("B", "black screen"),
    ("Tab", "slides ↔ water scene"),
    ("P", "presenter view (notes, timer, next slide)"),
    ("N", "speaker notes under the slide"),
    ("C", "controls on the audience screen"),
    ("- +", "widget: step size h down / up"),
    ("[ ]", "widget: step back / forward"),
    ("drag", "widget: move the start, orbit a view"),
    ("T Shift+T", "pause / reset the timer"),
    ("R", "reset this slide's tweaks"),
    ("Ctrl+1…9 1…9", "store / recall a tweak bookmark"),
    ("Ctrl+S", "write tweaks and typed equations back"),
    ("E", "export this slide as PNG"),
    ("D H L", "pen / highlighter / laser pointer"),
    ("1…5 (drawing)", "ink colour"),
    ("Ctrl+Z Shift+D", "undo a stroke / clear the slide's ink"),
    ("?", "this list"),
    ("Ctrl+Q", "quit"),
    ("Esc", "close overlays, stop drawing, fullscreen"),
];

/// The `?` list of the web player: what a browser page does (no presenter, ink, files or
/// quitting there).
pub const PLAYER_HELP: &[(&str, &str)] = &[
    ("→ ↓ Space PageDown click", "next slide"),
    ("← ↑ PageUp", "previous slide"),
    ("swipe left / right", "next / previous slide"),
    ("Home End", "first / last slide"),
    ("G number Enter", "go to slide (or #/number in the address)"),
    ("O", "overview of all slides"),
    (
        "Tab",
        "slides ↔ water scene (its \"controls\" button: the panel)",
    ),
    ("N", "speaker notes under the slide"),
    ("B", "black screen"),
    ("- +", "widget: step size h down / up"),
    ("[ ]", "widget: step back / forward"),
    ("drag", "widget: move the start"),
    ("R", "reset this slide's tweaks"),
    ("Ctrl+1…9 1…9", "store / recall a tweak bookmark"),
    ("?", "this list"),
    ("Esc", "close overlays"),
];

/// Whether the web player does `action` (the rest need a desktop: files, windows, the GPU
/// scene, ink).
pub fn in_player(action: Action) -> bool {
    use Action::*;
    !matches!(
        action,
        ToggleFullscreen
            | TogglePresenter
            | ToggleControls
            | TimerPause
            | TimerReset
            | ExportSlide
            | WriteBack
            | TogglePen
            | ToggleHighlighter
            | ToggleLaser
            | InkColor(_)
            | UndoInk
            | ClearInk
            | Quit
    )
}

/// The actions in `events`, read in `mode`.
pub fn actions(events: &[Event], mode: KeyMode) -> Vec<Action> {
    events.iter().filter_map(|e| action(e, mode)).collect()
}

/// While a text field has the keyboard (the presenter typing an equation), the only key the
/// app takes is Ctrl+S (write back); everything else, digits and letters included, is text.
pub fn while_editing(event: &Event) -> Option<Action> {
    match event {
        Event::Key {
            key: Key::S,
            pressed: true,
            modifiers,
            ..
        } if modifiers.command || modifiers.ctrl => Some(Action::WriteBack),
        Event::Key {
            key: Key::Q,
            pressed: true,
            modifiers,
            ..
        } if modifiers.command || modifiers.ctrl => Some(Action::Quit),
        _ => None,
    }
}

/// Whether the app handles `event` (so it can be taken out before widgets see it).
pub fn is_handled(event: &Event, mode: KeyMode) -> bool {
    action(event, mode).is_some() || matches!(event, Event::Key { key, .. } if claimed_key(*key))
}

/// Keys whose release means nothing to the app or to egui: the window drops their release
/// events, and [`crate::app::LecternApp`] forgets them as held once pressed. Each input event
/// costs egui two more frames, and on a software renderer a frame costs tens of ms, so a
/// clicker's PageDown is three frames instead of up to six.
pub fn release_is_ignored(key: Key) -> bool {
    claimed_key(key)
}

/// Keys we act on when pressed; their release (and repeats) are ours too.
fn claimed_key(key: Key) -> bool {
    matches!(
        key,
        Key::ArrowRight
            | Key::ArrowLeft
            | Key::ArrowDown
            | Key::ArrowUp
            | Key::Space
            | Key::PageDown
            | Key::PageUp
            | Key::Home
            | Key::End
            | Key::Tab
    )
}

fn action(event: &Event, mode: KeyMode) -> Option<Action> {
    use Action::*;
    match event {
        // '?' comes as text, whatever the keyboard layout puts it on.
        Event::Text(t) if t == "?" => Some(ToggleHelp),
        Event::Key {
            key,
            pressed: true,
            modifiers,
            ..
        } => {
            let digit = digit_of(*key);
            if mode == KeyMode::TypingNumber {
                return match (key, digit) {
                    (_, Some(d)) => Some(GotoDigit(d)),
                    (Key::Enter, _) => Some(GotoConfirm),
                    (Key::Backspace, _) => Some(GotoBackspace),
                    (Key::Escape, _) => Some(Escape),
                    _ => None,
                };
            }
            let ctrl = modifiers.command || modifiers.ctrl;
            if ctrl {
                return match (key, digit) {
                    (_, Some(d @ 1..=9)) => Some(BookmarkStore(d)),
                    (Key::S, _) => Some(WriteBack),
                    (Key::Q, _) => Some(Quit),
                    (Key::Z, _) if !modifiers.shift => Some(UndoInk),
                    _ => None,
                };
            }
            if modifiers.alt {
                return None;
            }
            Some(match key {
                Key::ArrowRight | Key::ArrowDown | Key::Space | Key::PageDown => Next,
                Key::ArrowLeft | Key::ArrowUp | Key::PageUp => Prev,
                Key::Home => First,
                Key::End => Last,
                Key::G => GotoStart,
                Key::O => ToggleOverview,
                Key::F | Key::F11 => ToggleFullscreen,
                Key::B => ToggleBlack,
                Key::Tab => ToggleMode,
                Key::Escape => Escape,
                Key::P => TogglePresenter,
                Key::C => ToggleControls,
                Key::R => ResetTweaks,
                Key::E => ExportSlide,
                Key::T if modifiers.shift => TimerReset,
                Key::T => TimerPause,
                Key::D if modifiers.shift => ClearInk,
                Key::D => TogglePen,
                Key::H => ToggleHighlighter,
                Key::L => ToggleLaser,
                Key::N => ToggleNotes,
                _ => match digit {
                    Some(d @ 1..=5) if mode == KeyMode::Drawing => InkColor(d - 1),
                    Some(d @ 1..=9) => BookmarkRecall(d),
                    _ => return None,
                },
            })
        }
        _ => None,
    }
}

fn digit_of(key: Key) -> Option<u8> {
    Some(match key {
        Key::Num0 => 0,
        Key::Num1 => 1,
        Key::Num2 => 2,
        Key::Num3 => 3,
        Key::Num4 => 4,
        Key::Num5 => 5,
        Key::Num6 => 6,
        Key::Num7 => 7,
        Key::Num8 => 8,
        Key::Num9 => 9,
        _ => return None,
    })
}

/// A key press as egui reports it, for tests.
pub fn press(key: Key, modifiers: Modifiers) -> Event {
    Event::Key {
        key,
        physical_key: None,
        pressed: true,
        repeat: false,
        modifiers,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Action::*;

    #[test]
    fn ctrl_q_quits_and_is_in_the_help_a_bare_q_does_nothing() {
        let ctrl = Modifiers::CTRL;
        assert_eq!(actions(&[press(Key::Q, ctrl)], KeyMode::Normal), vec![Quit]);
        assert_eq!(while_editing(&press(Key::Q, ctrl)), Some(Quit));
        assert!(actions(&[press(Key::Q, Modifiers::NONE)], KeyMode::Normal).is_empty());
        assert!(
            HELP.iter()
                .any(|(k, what)| *k == "Ctrl+Q" && *what == "quit")
        );
    }

    #[test]
    fn clicker_and_arrows() {
        let none = Modifiers::NONE;
        let ev = [
            press(Key::PageDown, none),
            press(Key::PageUp, none),
            press(Key::Space, none),
            press(Key::ArrowLeft, none),
            press(Key::End, none),
        ];
        assert_eq!(
            actions(&ev, KeyMode::Normal),
            vec![Next, Prev, Next, Prev, Last]
        );
    }

    #[test]
    fn digits_go_to_the_number_while_typing_and_to_bookmarks_otherwise() {
        let none = Modifiers::NONE;
        let ev = [
            press(Key::Num1, none),
            press(Key::Num2, none),
            press(Key::Enter, none),
        ];
        assert_eq!(
            actions(&ev, KeyMode::TypingNumber),
            vec![GotoDigit(1), GotoDigit(2), GotoConfirm]
        );
        assert_eq!(actions(&ev[..1], KeyMode::Normal), vec![BookmarkRecall(1)]);
        assert_eq!(
            actions(&[press(Key::Num3, Modifiers::CTRL)], KeyMode::Normal),
            vec![BookmarkStore(3)]
        );
    }

    #[test]
    fn while_typing_only_ctrl_s_is_a_key() {
        let none = Modifiers::NONE;
        for k in [
            Key::R,
            Key::P,
            Key::Num1,
            Key::Space,
            Key::ArrowRight,
            Key::B,
        ] {
            assert_eq!(while_editing(&press(k, none)), None, "{k:?}");
        }
        assert_eq!(
            while_editing(&press(Key::S, Modifiers::CTRL)),
            Some(WriteBack)
        );
    }

    #[test]
    fn n_shows_the_notes_and_the_player_keeps_to_what_a_page_can_do() {
        let none = Modifiers::NONE;
        assert_eq!(
            actions(&[press(Key::N, none)], KeyMode::Normal),
            vec![ToggleNotes]
        );
        assert!(in_player(ToggleNotes) && in_player(Next) && in_player(ToggleOverview));
        // scene mode runs on WebGL2 too (issue #25); files and windows do not
        assert!(in_player(ToggleMode) && !in_player(WriteBack) && !in_player(Quit));
        assert!(!in_player(TogglePresenter) && !in_player(ExportSlide));
        for (k, _) in PLAYER_HELP {
            assert!(!k.contains("Ctrl+S") && *k != "P", "{k}");
        }
        assert!(PLAYER_HELP.iter().any(|(k, _)| *k == "Tab"));
    }

    #[test]
    fn question_mark_from_text() {
        assert_eq!(
            actions(&[Event::Text("?".into())], KeyMode::Normal),
            vec![ToggleHelp]
        );
    }

    #[test]
    fn ink_keys_and_colours_while_drawing() {
        let none = Modifiers::NONE;
        let ev = [
            press(Key::D, none),
            press(Key::H, none),
            press(Key::L, none),
            press(Key::Z, Modifiers::CTRL),
            press(Key::D, Modifiers::SHIFT),
        ];
        let want = vec![TogglePen, ToggleHighlighter, ToggleLaser, UndoInk, ClearInk];
        assert_eq!(actions(&ev, KeyMode::Normal), want);
        assert_eq!(actions(&ev, KeyMode::Drawing), want);
        // Ctrl+Shift+Z is not undo (it would be redo elsewhere).
        assert!(
            actions(
                &[press(Key::Z, Modifiers::CTRL | Modifiers::SHIFT)],
                KeyMode::Normal
            )
            .is_empty()
        );
        // 1-5 pick a colour while drawing, and still recall bookmarks otherwise; 6 stays a
        // bookmark; Ctrl+digit always stores one.
        let digits = [
            press(Key::Num1, none),
            press(Key::Num5, none),
            press(Key::Num6, none),
            press(Key::Num2, Modifiers::CTRL),
        ];
        assert_eq!(
            actions(&digits, KeyMode::Drawing),
            vec![
                InkColor(0),
                InkColor(4),
                BookmarkRecall(6),
                BookmarkStore(2)
            ]
        );
        assert_eq!(
            actions(&digits, KeyMode::Normal),
            vec![
                BookmarkRecall(1),
                BookmarkRecall(5),
                BookmarkRecall(6),
                BookmarkStore(2)
            ]
        );
        // The keys are taken out of the input before slide widgets see them.
        assert!(is_handled(&press(Key::D, none), KeyMode::Normal));
        assert!(is_handled(
            &press(Key::Z, Modifiers::CTRL),
            KeyMode::Drawing
        ));
    }

    #[test]
    fn help_lists_every_ink_key() {
        let keys: String = HELP.iter().map(|(k, _)| *k).collect::<Vec<_>>().join(" ");
        for k in ["D", "H", "L", "Ctrl+Z", "Shift+D", "1…5"] {
            assert!(keys.contains(k), "{k} missing from the ? list");
        }
    }
}
