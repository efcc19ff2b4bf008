//! Tests of the pattern-brush options (`brush`): pieces fitted to the curve's length, and the
//! exemplar flipped and tinted.

use motif_core::{NoProgress, RgbaImage};

use crate::tests::{line, params};
use crate::{Fit, Flip, Input, Output, Params, PieceShape, synthesize};

/// Dark bars 10 px wide every 20 px, in rows `rows` of a 200 × 16 strip.
fn bars(rows: std::ops::Range<usize>) -> RgbaImage {
    RgbaImage::from_fn(200, 16, |x, y| if x % 20 < 10 && rows.contains(&y) { [40, 40, 40, 255] } else { [0; 4] })
}

/// Along a 130 px horizontal line, 16 px ribbon, 20 px pieces.
fn run(exemplar: &RgbaImage, params: &Params) -> Output {
    let curve = line(10.0, 40.0, 140.0, 40.0);
    let input = Input::new(exemplar, &curve);
    synthesize(&input, params, &mut NoProgress).unwrap()
}

/// The lengths of the opaque runs (alpha > 127) along the image's most opaque row, without the
/// first and last (which the curve's ends may cut).
fn bar_lengths(image: &RgbaImage) -> Vec<usize> {
    let opaque = |x: usize, y: usize| image.get(x, y)[3] > 127;
    let row = (0..image.height()).max_by_key(|&y| (0..image.width()).filter(|&x| opaque(x, y)).count()).unwrap();
    let mut runs = Vec::new();
    let mut length = 0;
    for x in 0..image.width() {
        if opaque(x, row) {
            length += 1;
        } else if length > 0 {
            runs.push(length);
            length = 0;
        }
    }
    runs[1..runs.len() - 1].to_vec()
}

fn mean(values: &[usize]) -> f64 {
    values.iter().sum::<usize>() as f64 / values.len() as f64
}

#[test]
fn stretched_pieces_are_a_whole_number_and_stretch_the_pattern_with_them() {
    let exemplar = bars(2..14);
    let plain = run(&exemplar, &params(16.0, 20.0));
    let stretched = run(&exemplar, &params(16.0, 20.0).with_fit(Fit::Stretch));
    // 130 / 20 = 6.5 pieces: 6 whole ones and a cut one, or 7 squeezed to 18.57 px.
    assert_eq!(plain.report.pieces, 7);
    assert_eq!(stretched.report.pieces, 7);
    let fitted = 130.0 / 7.0;
    assert!((stretched.report.fitted_piece_length - fitted).abs() < 1e-9, "{}", stretched.report.fitted_piece_length);
    assert_eq!(stretched.report.fit_gap, 0.0);
    // The 10 px bars are squeezed by the same factor as the pieces.
    let (plain_bars, stretched_bars) = (mean(&bar_lengths(&plain.image)), mean(&bar_lengths(&stretched.image)));
    assert!((plain_bars - 10.0).abs() < 0.35, "{plain_bars}");
    assert!((stretched_bars - 10.0 * fitted / 20.0).abs() < 0.35, "{stretched_bars}");
}

#[test]
fn spaced_pieces_are_whole_with_equal_gaps_up_to_the_curves_end() {
    let exemplar = bars(2..14);
    let spaced = run(&exemplar, &params(16.0, 20.0).with_fit(Fit::Space));
    // Six whole pieces; the 10 px left over makes five gaps of 2 px.
    assert_eq!(spaced.report.pieces, 6);
    assert!((spaced.report.fit_gap - 2.0).abs() < 1e-9, "{}", spaced.report.fit_gap);
    assert_eq!(spaced.report.fitted_piece_length, 20.0);
    // The bars are not stretched; every piece is whole, so the last bar is too.
    let lengths = bar_lengths(&spaced.image);
    assert!((mean(&lengths) - 10.0).abs() < 0.35, "{lengths:?}");
    assert_eq!(spaced.report.empty_pieces, 0);
}

#[test]
fn spaced_pieces_of_a_pattern_with_no_clear_column_cut_it_least() {
    // Bars joined by a thin line through the middle row: every window's sides cross the line, and
    // the spaced pieces cut only the line, never a bar.
    let exemplar = RgbaImage::from_fn(200, 16, |x, y| match (x % 20 < 10, y) {
        (true, 2..=13) | (false, 7) => [40, 40, 40, 255],
        _ => [0; 4],
    });
    let spaced = run(&exemplar, &params(16.0, 20.0).with_fit(Fit::Space));
    assert_eq!(spaced.report.pieces, 6);
    // The bars, measured along a row the line does not cross, are whole.
    let image = &spaced.image;
    let row = (0..image.height())
        .filter(|&y| (0..image.width()).any(|x| image.get(x, y)[3] > 127))
        .nth(3)
        .expect("rows of bars");
    let mut runs = Vec::new();
    let mut length = 0;
    for x in 0..image.width() {
        if image.get(x, row)[3] > 127 {
            length += 1;
        } else if length > 0 {
            runs.push(length);
            length = 0;
        }
    }
    assert!(runs.len() >= 6 && runs.iter().all(|&r| (9..=11).contains(&r)), "{runs:?}");
}

#[test]
fn stretching_rigid_pieces_is_refused_by_name() {
    let refused = params(16.0, 20.0).with_fit(Fit::Stretch).with_piece_shape(PieceShape::Rigid);
    let message = refused.validate().unwrap_err().to_string();
    assert!(message.contains("fit") && message.contains("bent"), "{message}");
    params(16.0, 20.0).with_fit(Fit::Space).with_piece_shape(PieceShape::Rigid).validate().unwrap();
}

#[test]
fn a_flip_across_puts_the_pattern_on_the_other_side_of_the_curve() {
    // Bars red in their top half and blue in their bottom half, as tall as the ribbon: the red
    // centroid lies on one side of the line, and flipped across on the other, as far from it.
    let exemplar = RgbaImage::from_fn(200, 16, |x, y| match (x % 20 < 10, y) {
        (true, 1..=7) => [200, 20, 20, 255],
        (true, 8..=14) => [20, 20, 200, 255],
        _ => [0; 4],
    });
    let red_offset = |output: &Output| {
        let image = &output.image;
        let line_y = 40.0 - output.report.canvas_origin[1];
        let (mut sum, mut count) = (0.0, 0.0);
        for y in 0..image.height() {
            for x in 0..image.width() {
                let [r, _, b, a] = image.get(x, y);
                if a > 127 && r > b {
                    sum += y as f64 + 0.5 - line_y;
                    count += 1.0;
                }
            }
        }
        sum / count
    };
    let plain = red_offset(&run(&exemplar, &params(16.0, 20.0)));
    let flipped = red_offset(&run(&exemplar, &params(16.0, 20.0).with_flip(Flip::Across)));
    assert!(plain.abs() > 3.0, "{plain}");
    assert!((plain + flipped).abs() < 0.5, "{plain} {flipped}");
}

#[test]
fn a_tint_turns_black_into_the_colour_and_keeps_the_alpha() {
    let exemplar = bars(2..14);
    let colour = [180, 30, 60];
    let plain = run(&exemplar, &params(16.0, 20.0));
    let tinted = run(&exemplar, &params(16.0, 20.0).with_tint(Some(colour)));
    // The bars' grey (luma 40 of 255) as a tint: each channel c + (255 − c)·40/255.
    let expected = colour.map(|c| (u32::from(c) + ((255 - u32::from(c)) * 40 + 127) / 255) as u8);
    let mut solid = 0;
    for (a, b) in plain.image.pixels().iter().zip(tinted.image.pixels()) {
        assert_eq!(a[3], b[3], "alpha kept");
        if b[3] == 255 {
            assert_eq!([b[0], b[1], b[2]], expected);
            solid += 1;
        }
    }
    assert!(solid > 500, "{solid}");
}

#[test]
fn end_tiles_are_drawn_whole_at_the_curves_ends() {
    // Bars of 10 px, with a distinct cap: a 30 px red block at columns 170..200 of the exemplar.
    let exemplar = RgbaImage::from_fn(200, 16, |x, y| match (x, y) {
        (170..=199, 2..=13) => [200, 20, 20, 255],
        (_, 2..=13) if x % 20 < 10 && x < 160 => [40, 40, 40, 255],
        _ => [0; 4],
    });
    let tiled = params(16.0, 20.0).with_start_tile(Some([170, 200])).with_end_tile(Some([170, 200]));
    let output = run(&exemplar, &tiled);
    let pieces = &output.pieces;
    // 130 px: a 29 px start tile (column centres 170.5 to 199.5), 72 px of pieces, a 29 px end tile.
    let column = |piece: &crate::PlacedPiece| piece.position.map(|[x, _]| x);
    assert_eq!(column(&pieces[0]), Some(170));
    assert_eq!(column(&pieces[pieces.len() - 1]), Some(170));
    assert!(pieces[1..pieces.len() - 1].iter().all(|piece| column(piece) < Some(160)), "{pieces:?}");
    assert_eq!((pieces[0].arc, pieces[pieces.len() - 1].arc), ([0.0, 29.0], [101.0, 130.0]));
    // Red only at the two ends of the line, 30 px each.
    let image = &output.image;
    let row = |y: usize| -> Vec<[u8; 4]> { (0..image.width()).map(|x| image.get(x, y)).collect() };
    let middle = (0..image.height()).max_by_key(|&y| row(y).iter().filter(|p| p[3] > 127).count()).unwrap();
    let red: Vec<usize> =
        row(middle).iter().enumerate().filter(|(_, p)| p[3] > 127 && p[0] > 150).map(|(x, _)| x).collect();
    let (first, last) = (red[0], red[red.len() - 1]);
    assert!((56..=60).contains(&red.len()), "{red:?}");
    assert!(red.iter().all(|&x| x < first + 30 || x + 30 > last), "{red:?}");
    assert!(last - first > 100, "{red:?}");
    // A tile exactly one piece long has the pieces' frame, and still its own positions.
    let same_frame = run(&exemplar, &params(16.0, 20.0).with_start_tile(Some([170, 191])));
    assert_eq!(same_frame.pieces[0].arc, [0.0, 20.0]);
    assert_eq!(column(&same_frame.pieces[0]), Some(170));
    assert!(same_frame.pieces[1..].iter().all(|piece| column(piece) < Some(160)), "{:?}", same_frame.pieces);
    // Tiles need an open curve and columns inside the exemplar.
    let closed = crate::tests::circle(100.0, 100.0, 60.0, 64);
    let input = Input::new(&exemplar, &closed);
    let message = synthesize(&input, &tiled, &mut NoProgress).unwrap_err().to_string();
    assert!(message.contains("start-tile") && message.contains("closed"), "{message}");
    let outside = params(16.0, 20.0).with_end_tile(Some([190, 210]));
    let curve = line(10.0, 40.0, 140.0, 40.0);
    let input = Input::new(&exemplar, &curve);
    let message = synthesize(&input, &outside, &mut NoProgress).unwrap_err().to_string();
    assert!(message.contains("end-tile") && message.contains("200"), "{message}");
}

/// Bars of 10 px with a distinct corner piece: a red block at columns 170..200.
fn bars_with_red_tile() -> RgbaImage {
    RgbaImage::from_fn(200, 16, |x, y| match (x, y) {
        (170..=199, 2..=13) => [200, 20, 20, 255],
        (_, 2..=13) if x % 20 < 10 && x < 160 => [40, 40, 40, 255],
        _ => [0; 4],
    })
}

/// The canvas points where the render is opaque and red.
fn red_pixels(image: &RgbaImage) -> Vec<(usize, usize)> {
    let mut red = Vec::new();
    for y in 0..image.height() {
        for x in 0..image.width() {
            let p = image.get(x, y);
            if p[3] > 127 && p[0] > 150 && p[1] < 100 {
                red.push((x, y));
            }
        }
    }
    red
}

/// A closed 160 × 120 rectangle at (20, 20): four 90° corners.
fn rectangle_frame() -> motif_core::Polyline {
    motif_core::Polyline::new(
        [(20.0, 20.0), (180.0, 20.0), (180.0, 140.0), (20.0, 140.0)]
            .map(|(x, y)| motif_core::Point::new(x, y))
            .to_vec(),
        true,
    )
    .unwrap()
}

#[test]
fn corner_tiles_are_drawn_at_the_corners_of_a_closed_frame_and_nowhere_else() {
    let exemplar = bars_with_red_tile();
    // A 160 × 120 rectangle, closed: four 90° corners.
    let frame = rectangle_frame();
    let mut with_corners = params(16.0, 20.0).with_corner_tile(Some([170, 200]));
    with_corners.canvas = crate::Canvas::Size { width: 200, height: 160 };
    let output = synthesize(&Input::new(&exemplar, &frame), &with_corners, &mut NoProgress).unwrap();
    assert_eq!(output.report.corner_tiles, 4);
    let column = |piece: &crate::PlacedPiece| piece.position.map(|[x, _]| x);
    let tiles: Vec<&crate::PlacedPiece> = output.pieces.iter().filter(|piece| column(piece) == Some(170)).collect();
    assert_eq!(tiles.len(), 4, "{:?}", output.pieces);
    // Each tile is 29 px of arc and holds a corner: the rectangle's corner is nearer to its
    // middle than to its ends.
    let corners = [(20.0, 20.0), (180.0, 20.0), (180.0, 140.0), (20.0, 140.0)];
    for tile in &tiles {
        assert!((tile.arc[1] - tile.arc[0] - 29.0).abs() < 1e-9, "{:?}", tile.arc);
        let [a, b, c, d] = tile.quad;
        let centre = ((a[0] + b[0] + c[0] + d[0]) / 4.0, (a[1] + b[1] + c[1] + d[1]) / 4.0);
        let nearest = corners
            .iter()
            .map(|(x, y)| motif_core::math::hypot(x - centre.0, y - centre.1))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < 20.0, "tile centred at {centre:?}");
    }
    // Red shows at the four corners only (within 30 px of one), and no other piece draws it.
    let red = red_pixels(&output.image);
    assert!(red.len() > 4 * 150, "{}", red.len());
    for (x, y) in &red {
        let near = corners.iter().any(|(cx, cy)| (*x as f64 - cx).abs() < 30.0 && (*y as f64 - cy).abs() < 30.0);
        assert!(near, "red at ({x}, {y})");
    }
    for corner in corners {
        let here =
            red.iter().filter(|(x, y)| (*x as f64 - corner.0).abs() < 30.0 && (*y as f64 - corner.1).abs() < 30.0);
        assert!(here.count() > 100, "no tile at {corner:?}");
    }
    assert!(output.pieces.iter().filter(|piece| column(piece) != Some(170)).all(|piece| column(piece) < Some(160)));
}

#[test]
fn a_curve_without_corners_is_drawn_as_without_a_corner_tile() {
    let exemplar = bars_with_red_tile();
    let circle = crate::tests::circle(100.0, 100.0, 60.0, 90);
    let plain = params(16.0, 20.0);
    let input = Input::new(&exemplar, &circle);
    let without = synthesize(&input, &plain, &mut NoProgress).unwrap();
    let with = synthesize(&input, &plain.clone().with_corner_tile(Some([170, 200])), &mut NoProgress).unwrap();
    assert_eq!(with.report.corner_tiles, 0);
    assert_eq!(with.image, without.image);
}

#[test]
fn the_corner_angle_decides_which_turns_get_a_tile_on_an_open_path() {
    let exemplar = bars_with_red_tile();
    // A 70° turn and then a 120° turn (the second back down), 100 px apart, with straight ends.
    let turn = |degrees: f64| degrees.to_radians();
    let a = motif_core::Point::new(20.0, 100.0);
    let b = motif_core::Point::new(120.0, 100.0);
    let c = b + motif_core::Vec2::new(
        100.0 * motif_core::math::cos(turn(-70.0)),
        100.0 * motif_core::math::sin(turn(-70.0)),
    );
    let d =
        c + motif_core::Vec2::new(100.0 * motif_core::math::cos(turn(50.0)), 100.0 * motif_core::math::sin(turn(50.0)));
    let path = motif_core::Polyline::new(vec![a, b, c, d], false).unwrap();
    let input = Input::new(&exemplar, &path);
    let tiles_at = |angle: f64| {
        let tiled = params(16.0, 20.0).with_corner_tile(Some([170, 200])).with_corner_angle(angle);
        synthesize(&input, &tiled, &mut NoProgress).unwrap().report.corner_tiles
    };
    assert_eq!(tiles_at(60.0), 2);
    assert_eq!(tiles_at(90.0), 1);
    assert_eq!(tiles_at(150.0), 0);
    // With a start tile too: the ends and the corners each get theirs.
    let both = params(16.0, 20.0).with_corner_tile(Some([170, 200])).with_start_tile(Some([170, 200]));
    let output = synthesize(&input, &both, &mut NoProgress).unwrap();
    assert_eq!(output.report.corner_tiles, 2);
    assert_eq!(output.pieces[0].position.map(|[x, _]| x), Some(170));
    let bad = params(16.0, 20.0).with_corner_tile(Some([170, 200])).with_corner_angle(5.0);
    assert!(synthesize(&input, &bad, &mut NoProgress).unwrap_err().to_string().contains("corner-angle"));
}

#[test]
fn tiles_from_images_of_their_own_are_drawn_whole_and_only_as_tiles() {
    // Grey bars as the exemplar; a red cap 30 px wide and a blue corner piece as images of their own.
    let exemplar = bars(2..14);
    let block = |colour: [u8; 4]| {
        RgbaImage::from_fn(
            34,
            16,
            move |x, y| if (2..32).contains(&x) && (2..14).contains(&y) { colour } else { [0; 4] },
        )
    };
    let images = [block([200, 20, 20, 255]), block([20, 20, 200, 255])];
    let curve = line(10.0, 40.0, 140.0, 40.0);
    let input = Input::new(&exemplar, &curve).with_more_exemplars(&images[..1]);
    let capped = params(16.0, 20.0).with_tile_exemplars([Some(1), Some(1), None]);
    let output = synthesize(&input, &capped, &mut NoProgress).unwrap();
    let pieces = &output.pieces;
    // The caps are the images' whole pattern: 29 px of arc, from exemplar 1; the pieces between
    // never copy an image tile.
    assert_eq!((pieces[0].exemplar, pieces[pieces.len() - 1].exemplar), (1, 1));
    assert_eq!((pieces[0].arc, pieces[pieces.len() - 1].arc), ([0.0, 29.0], [101.0, 130.0]));
    assert!(pieces[1..pieces.len() - 1].iter().all(|piece| piece.exemplar == 0), "{pieces:?}");
    // Red in two 29 px runs at the line's two ends (the canvas is fitted: the line is 130 px).
    let red = red_pixels(&output.image);
    let (low, high) = (red.iter().map(|p| p.0).min().unwrap(), red.iter().map(|p| p.0).max().unwrap());
    assert!(high - low > 125 && red.iter().all(|&(x, _)| x < low + 30 || x + 30 > high), "{low} {high}");
    assert!(red.len() > 2 * 250, "{}", red.len());
    // An image corner tile on a closed frame: blue at the four corners.
    let frame = rectangle_frame();
    let input = Input::new(&exemplar, &frame).with_more_exemplars(&images[1..]);
    let cornered = params(16.0, 20.0).with_tile_exemplars([None, None, Some(1)]);
    let output = synthesize(&input, &cornered, &mut NoProgress).unwrap();
    assert_eq!(output.report.corner_tiles, 4);
    assert_eq!(output.pieces.iter().filter(|piece| piece.exemplar == 1).count(), 4);
    // An index that names no image is refused by name.
    let missing = params(16.0, 20.0).with_tile_exemplars([Some(3), None, None]);
    let message = synthesize(&Input::new(&exemplar, &curve), &missing, &mut NoProgress).unwrap_err().to_string();
    assert!(message.contains("start-tile-image"), "{message}");
}

/// A frieze of rings on a thin line that runs on past them at both ends (a "thin-ended frieze").
fn thin_ended_frieze() -> RgbaImage {
    RgbaImage::from_fn(240, 24, |x, y| {
        let line = (11..13).contains(&y);
        let ring = (72..170).step_by(24).any(|cx: usize| {
            let (dx, dy) = (x as f64 - cx as f64, y as f64 - 11.5);
            let r = motif_core::math::hypot(dx, dy);
            r > 6.0 && r < 9.5
        });
        if line || ring { [30, 30, 30, 255] } else { [0; 4] }
    })
}

#[test]
fn a_thin_strip_repeated_at_no_cost_is_found_and_the_motif_drawn_instead() {
    let exemplar = thin_ended_frieze();
    let curve = line(10.0, 40.0, 410.0, 40.0);
    let input = Input::new(&exemplar, &curve);
    let output = synthesize(&input, &params(30.0, 20.0), &mut NoProgress).unwrap();
    // The line alone seams at no cost; the rings cost something at some seams. The first optimum
    // repeats the line; the check takes the thin windows out and the rings are drawn.
    let thin = output.report.thin_strip.clone().expect("the thin strip is found");
    assert!(thin.share_before < 0.5 && thin.share_after > 0.9, "{thin:?}");
    assert!(thin.positions_dropped > 0);
    assert!(output.report.warnings.iter().any(|w| w.contains("thin strip")), "{:?}", output.report.warnings);
    // Rings put about four times the line's ink into every piece.
    let ink = output.image.count_alpha_at_least(128);
    assert!(ink > 3 * 400 * 2, "{ink}");
    // Variety now has motifs to vary: more distinct windows than without it.
    let varied = synthesize(&input, &params(30.0, 20.0).with_variety(300.0), &mut NoProgress).unwrap();
    assert!(
        varied.report.distinct_windows > output.report.distinct_windows,
        "{} {}",
        varied.report.distinct_windows,
        output.report.distinct_windows
    );
    // A pattern whose pieces hold their motifs is left as it is.
    let bars = run(&bars(2..14), &params(16.0, 20.0));
    assert!(bars.report.thin_strip.is_none());
}
