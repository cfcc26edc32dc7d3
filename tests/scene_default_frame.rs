//! The default frame as a new user first sees it (`lectern present`, `Tab`, or `render-scene`
//! at the scene file's camera): a blue sky above a paler horizon, and schools of fish that
//! show as schools through the water.

use std::path::Path;

use lectern::render::{DebugView, Headless};
use lectern::scene;

const SIZE: (u32, u32) = (640, 360);

fn headless(edit: &dyn Fn(&mut scene::Scene)) -> Headless {
    let mut s = scene::load_scene(Path::new(scene::DEFAULT_SCENE)).unwrap();
    edit(&mut s);
    let mut h = Headless::new(s, Path::new("shaders")).unwrap();
    h.sim.set_time(2.5);
    h
}

fn luma(p: &image::Rgba<u8>) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// The mean colour of rows `rows` (0–1 per channel).
fn mean_rgb(img: &image::RgbaImage, rows: std::ops::Range<u32>) -> [f64; 3] {
    let mut sum = [0.0; 3];
    let n = (rows.len() as u32 * img.width()) as f64;
    for y in rows {
        for x in 0..img.width() {
            let p = img.get_pixel(x, y);
            (0..3).for_each(|c| sum[c] += p[c] as f64 / 255.0);
        }
    }
    sum.map(|s| s / n)
}

/// (hue in degrees, HSV saturation 0–1, luma 0–255) of a mean colour.
fn hue_saturation_luma([r, g, b]: [f64; 3]) -> (f64, f64, f64) {
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    let chroma = max - min;
    let hue = if chroma <= 0.0 {
        0.0
    } else if max == r {
        60.0 * ((g - b) / chroma).rem_euclid(6.0)
    } else if max == g {
        60.0 * ((b - r) / chroma + 2.0)
    } else {
        60.0 * ((r - g) / chroma + 4.0)
    };
    let saturation = if max > 0.0 { chroma / max } else { 0.0 };
    (
        hue,
        saturation,
        255.0 * (0.2126 * r + 0.7152 * g + 0.0722 * b),
    )
}

/// The first row from the top where most pixels are water in the normals view (the sky is
/// black there): the horizon as drawn.
fn horizon_row(h: &mut Headless) -> u32 {
    h.settings.debug_view = DebugView::Normals;
    let img = h.render(SIZE).unwrap();
    h.settings.debug_view = DebugView::None;
    (0..img.height())
        .find(|&y| {
            let water = (0..img.width())
                .filter(|&x| img.get_pixel(x, y).0[..3].iter().any(|&c| c >= 8))
                .count();
            water > img.width() as usize / 2
        })
        .unwrap_or(img.height())
}

/// The default frame's sky is blue at the top (hue 195–240°, HSV saturation ≥ 25 %) and paler
/// just above the horizon (less saturated, brighter). The frame before this (the camera towards
/// a sun 10° up, no white balance) had a pale yellow-grey top: hue ~100°, saturation ~1 %.
#[test]
fn the_default_frame_shows_a_blue_sky_above_a_paler_horizon() {
    let mut h = headless(&|_| {});
    let horizon = horizon_row(&mut h);
    let img = h.render(SIZE).unwrap();
    let hgt = img.height();
    assert!(
        horizon > hgt / 4 && horizon < 3 * hgt / 4,
        "the horizon at row {horizon} of {hgt}"
    );
    let top = hue_saturation_luma(mean_rgb(&img, 0..hgt / 20));
    let band = hue_saturation_luma(mean_rgb(&img, horizon - hgt / 10..horizon - 2));
    eprintln!(
        "horizon row {horizon}; top: hue {:.1}°, saturation {:.3}, luma {:.1}; above the horizon: hue {:.1}°, saturation {:.3}, luma {:.1}",
        top.0, top.1, top.2, band.0, band.1, band.2
    );
    assert!((195.0..=240.0).contains(&top.0), "top hue {:.1}°", top.0);
    assert!(top.1 >= 0.25, "top saturation {:.3}", top.1);
    assert!(
        band.1 < top.1 - 0.1,
        "the horizon is paler: saturation {:.3} vs {:.3}",
        band.1,
        top.1
    );
    assert!(
        band.2 > top.2 + 5.0,
        "the horizon is brighter: luma {:.1} vs {:.1}",
        band.2,
        top.2
    );
    // and the sun disc is in the frame: its white-hot pixels, above the horizon
    let sun_px = img
        .enumerate_pixels()
        .filter(|(_, y, p)| *y < horizon && luma(p) > 250.0)
        .count();
    assert!(
        sun_px > 20,
        "the sun disc in the frame: {sun_px} white pixels"
    );
}

/// The connected regions (4-neighbours) of `mask` (row-major, `w` wide): for each, its pixel
/// count and bounding box area, largest first.
fn clusters(mask: &[bool], w: usize) -> Vec<(usize, usize)> {
    let h = mask.len() / w;
    let mut seen = vec![false; mask.len()];
    let mut out = Vec::new();
    for start in 0..mask.len() {
        if !mask[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        let mut stack = vec![start];
        let (mut n, mut x0, mut x1, mut y0, mut y1) = (0, w, 0, h, 0);
        while let Some(i) = stack.pop() {
            let (x, y) = (i % w, i / w);
            n += 1;
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            let next = [
                (x > 0).then(|| i - 1),
                (x + 1 < w).then(|| i + 1),
                (y > 0).then(|| i - w),
                (y + 1 < h).then(|| i + w),
            ];
            for j in next.into_iter().flatten() {
                if mask[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        out.push((n, (x1 - x0 + 1) * (y1 - y0 + 1)));
    }
    out.sort_by(|a, b| b.0.cmp(&a.0));
    out
}

/// The fish in the default frame are seen, and seen as schools: the pixels that the fish
/// change (fish on against none, by more than 20/255 of luma: the fish and their shadows)
/// cover a visible share of the frame, and the largest connected patch of them is a school's
/// worth of pixels inside a box much smaller than the frame (measured: 9.2 %, 3.5 % in a box of
/// 9.2 %). A measure of presence and clustering, not of legibility: the frame before this (a
/// low camera, 1500 fish in six schools over a 22 m box, 3 m deep) changed 10.9 % of the frame,
/// its largest patch 3.0 % in a box of 6.2 %, mostly by smearing the refraction where no fish
/// could be made out; the golden `scene-t2.5.png` and `docs/scene-screenshot.png` show the
/// difference.
#[test]
fn the_default_frame_shows_schools_of_fish_through_the_water() {
    let with = headless(&|_| {}).render(SIZE).unwrap();
    let without = headless(&|s| s.school.count = 0).render(SIZE).unwrap();
    let mask: Vec<bool> = with
        .pixels()
        .zip(without.pixels())
        .map(|(p, q)| (luma(p) - luma(q)).abs() > 20.0)
        .collect();
    let frame = mask.len() as f64;
    let changed = mask.iter().filter(|&&m| m).count() as f64 / frame;
    let patches = clusters(&mask, SIZE.0 as usize);
    let &(largest, bbox) = patches.first().expect("the fish change some pixels");
    let (largest, bbox) = (largest as f64 / frame, bbox as f64 / frame);
    eprintln!(
        "fish change {:.1} % of the frame; largest patch {:.1} % in a box of {:.1} %",
        100.0 * changed,
        100.0 * largest,
        100.0 * bbox
    );
    assert!(changed >= 0.05, "the fish change {changed:.3} of the frame");
    assert!(
        largest >= 0.02,
        "the largest patch is {largest:.3} of the frame"
    );
    assert!(
        bbox <= 0.25,
        "the largest patch spans {bbox:.3} of the frame"
    );
}
