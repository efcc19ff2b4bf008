//! Seeded synthetic inputs for demos, benchmarks and tests: a map-like segment guide and a
//! hand-drawn-looking style for it, smooth multi-channel guides, and footage filmed over a still
//! photo with its exact motion (for video stylization).

use motif_core::random::Rng;
use motif_core::{FloatImage, SeedStreams, math};

use crate::MotionField;

/// Colours of the map segments: water, grass, built-up, sand, road (like the paper's Fig. 1).
pub const MAP_PALETTE: [[f32; 3]; 5] =
    [[0.55, 0.75, 0.95], [0.75, 0.9, 0.6], [0.95, 0.8, 0.85], [0.95, 0.9, 0.7], [1.0, 1.0, 1.0]];

/// A map-like guide of flat colours: `segments` (2..=5) regions with wavy borders from a warped
/// Voronoi diagram, and, with 5 segments, white roads on top. Exact palette, no anti-aliasing.
pub fn map_guide(width: usize, height: usize, segments: usize, seed: u64) -> FloatImage {
    let segments = segments.clamp(2, 5);
    let regions = if segments == 5 { 4 } else { segments };
    let mut stream = SeedStreams::new(seed).stream("map guide", 0);
    let sites: Vec<(f32, f32, usize)> = (0..3 * regions)
        .map(|i| (stream.random::<f32>() * width as f32, stream.random::<f32>() * height as f32, i % regions))
        .collect();
    let phase: [f32; 4] = std::array::from_fn(|_| stream.random::<f32>() * 6.3);
    let roads: Vec<(f32, f32, f32)> = (0..2)
        .map(|_| {
            let angle = stream.random::<f32>() * std::f32::consts::PI;
            (
                math::cos_f32(angle),
                math::sin_f32(angle),
                (stream.random::<f32>() - 0.5) * 0.5 * width.min(height) as f32,
            )
        })
        .collect();
    let scale = width.max(height) as f32;
    let mut data = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for x in 0..width {
            let (fx, fy) = (x as f32, y as f32);
            let wx = fx
                + 0.04 * scale * math::sin_f32(fy * 9.0 / scale + phase[0])
                + 0.02 * scale * math::sin_f32(fy * 23.0 / scale + phase[1]);
            let wy = fy
                + 0.04 * scale * math::sin_f32(fx * 8.0 / scale + phase[2])
                + 0.02 * scale * math::sin_f32(fx * 19.0 / scale + phase[3]);
            let region = sites
                .iter()
                .map(|&(sx, sy, r)| ((sx - wx).powi(2) + (sy - wy).powi(2), r))
                .fold((f32::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a })
                .1;
            let mut colour = MAP_PALETTE[region];
            if segments == 5 {
                let (cx, cy) = (fx - width as f32 / 2.0, fy - height as f32 / 2.0);
                let on_road =
                    roads.iter().any(|&(c, s, offset)| (cx * c + cy * s - offset).abs() < 0.012 * scale + 1.5);
                if on_road {
                    colour = MAP_PALETTE[4];
                }
            }
            data.extend_from_slice(&colour);
        }
    }
    FloatImage::from_data(width, height, 3, data).expect("sizes match")
}

/// A crayon-like style for a segment guide: each guide colour becomes a darker, hatched,
/// noisy version of itself, with strokes in a direction of its own.
pub fn crayon_style(guide: &FloatImage, seed: u64) -> FloatImage {
    let channels = guide.channels().min(3);
    let mut stream = SeedStreams::new(seed).stream("crayon", 0);
    let mut out = FloatImage::new(guide.width(), guide.height(), 3);
    for y in 0..guide.height() {
        for x in 0..guide.width() {
            let g = guide.pixel(x, y);
            let hue = g.iter().take(channels).enumerate().map(|(c, v)| v * (c + 1) as f32).sum::<f32>();
            let angle = hue * 2.1;
            let t = x as f32 * math::cos_f32(angle) + y as f32 * math::sin_f32(angle);
            let stroke = 0.5 + 0.5 * math::sin_f32(t * 0.9 + math::sin_f32(y as f32 * 0.21) * 2.0);
            let grain = stream.random::<f32>();
            let shade = 0.55 + 0.3 * stroke + 0.15 * grain;
            let pixel = out.pixel_mut(x, y);
            for c in 0..3 {
                let base = g[c.min(channels - 1)];
                pixel[c] = (base * shade + 0.08 * (grain - 0.5)).clamp(0.0, 1.0);
            }
        }
    }
    out
}

/// A smooth random image of `channels` channels (sums of sinusoids plus light noise), for guide
/// channels such as gradients or normals in benchmarks.
pub fn smooth_field(width: usize, height: usize, channels: usize, seed: u64) -> FloatImage {
    let mut stream = SeedStreams::new(seed).stream("smooth field", 0);
    let waves: Vec<[f32; 3]> = (0..4 * channels)
        .map(|_| [stream.random::<f32>() * 0.05, stream.random::<f32>() * 0.05, stream.random::<f32>() * 6.3])
        .collect();
    let mut data = Vec::with_capacity(width * height * channels);
    for y in 0..height {
        for x in 0..width {
            for c in 0..channels {
                let mut v = 0.5;
                for wave in &waves[c * 4..(c + 1) * 4] {
                    v += 0.11 * math::sin_f32(wave[0] * x as f32 + wave[1] * y as f32 + wave[2]);
                }
                data.push((v + 0.02 * (stream.random::<f32>() - 0.5)).clamp(0.0, 1.0));
            }
        }
    }
    FloatImage::from_data(width, height, channels, data).expect("sizes match")
}

/// A camera path over a still photo: the frame's centre in photo pixels and its zoom (frame
/// pixels per photo pixel), the centre moving linearly and the zoom geometrically from start to
/// end. Zooms of 1 and more keep the photo sharp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraPath {
    /// Centre of the first frame, in photo pixels.
    pub start_centre: [f64; 2],
    /// Centre of the last frame.
    pub end_centre: [f64; 2],
    /// Zoom of the first frame.
    pub start_zoom: f64,
    /// Zoom of the last frame.
    pub end_zoom: f64,
}

/// Frames filmed over a still photo along a [`CameraPath`], with their exact motion.
#[derive(Debug, Clone, PartialEq)]
pub struct Footage {
    /// The frames.
    pub frames: Vec<FloatImage>,
    /// `motion[i]` carries frame `i` to frame `i + 1` (exact, from the path).
    pub motion: Vec<MotionField>,
    centres: Vec<[f64; 2]>,
    zooms: Vec<f64>,
}

impl Footage {
    /// Where frame `frame`'s pixel centre `(x, y)` lies in frame `other`, in pixels.
    fn position_in(&self, frame: usize, other: usize, x: usize, y: usize) -> [f64; 2] {
        let (width, height) = (self.frames[0].width() as f64, self.frames[0].height() as f64);
        let photo = [
            self.centres[frame][0] + (x as f64 + 0.5 - 0.5 * width) / self.zooms[frame],
            self.centres[frame][1] + (y as f64 + 0.5 - 0.5 * height) / self.zooms[frame],
        ];
        [
            (photo[0] - self.centres[other][0]) * self.zooms[other] + 0.5 * width,
            (photo[1] - self.centres[other][1]) * self.zooms[other] + 0.5 * height,
        ]
    }

    /// `image`, aligned with frame `from`, as frame `frame` shows it, and per pixel whether it
    /// was inside frame `from` (the ideal result of carrying a keyframe's style along).
    pub fn carried(&self, image: &FloatImage, from: usize, frame: usize) -> (FloatImage, Vec<bool>) {
        let (width, height) = (image.width(), image.height());
        let mut out = FloatImage::new(width, height, image.channels());
        let mut visible = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                let [px, py] = self.position_in(frame, from, x, y);
                image.sample_bilinear(px, py, out.pixel_mut(x, y));
                visible.push(px >= 0.0 && py >= 0.0 && px <= width as f64 && py <= height as f64);
            }
        }
        (out, visible)
    }
}

/// `frames` frames of `width × height` filmed over `photo` along `path` (bilinear samples).
pub fn pan_and_zoom(photo: &FloatImage, width: usize, height: usize, frames: usize, path: CameraPath) -> Footage {
    let along = |i: usize| if frames > 1 { i as f64 / (frames - 1) as f64 } else { 0.0 };
    let centres: Vec<[f64; 2]> = (0..frames)
        .map(|i| {
            let t = along(i);
            [
                path.start_centre[0] + t * (path.end_centre[0] - path.start_centre[0]),
                path.start_centre[1] + t * (path.end_centre[1] - path.start_centre[1]),
            ]
        })
        .collect();
    let zooms: Vec<f64> =
        (0..frames).map(|i| path.start_zoom * math::powf(path.end_zoom / path.start_zoom, along(i))).collect();
    let mut footage = Footage { frames: Vec::new(), motion: Vec::new(), centres, zooms };
    for i in 0..frames {
        let mut frame = FloatImage::new(width, height, photo.channels());
        for y in 0..height {
            for x in 0..width {
                let px = footage.centres[i][0] + (x as f64 + 0.5 - 0.5 * width as f64) / footage.zooms[i];
                let py = footage.centres[i][1] + (y as f64 + 0.5 - 0.5 * height as f64) / footage.zooms[i];
                photo.sample_bilinear(px, py, frame.pixel_mut(x, y));
            }
        }
        footage.frames.push(frame);
    }
    for i in 1..frames {
        let mut motion = MotionField::zero(width, height);
        for y in 0..height {
            for x in 0..width {
                let [px, py] = footage.position_in(i, i - 1, x, y);
                motion.offsets[y * width + x] = [(px - 0.5 - x as f64) as f32, (py - 0.5 - y as f64) as f32];
            }
        }
        footage.motion.push(motion);
    }
    footage
}

/// A keyframe "painted" over `frame` for demos and tests of video stylization: flat tones (the
/// luma posterized, the hue kept), dark outlines along the frame's edges, and the weave of `canvas` (a real texture)
/// pressed into the paint. The weave is detail that must stay on the surface as the camera moves.
pub fn painted_keyframe(frame: &FloatImage, canvas: &FloatImage) -> FloatImage {
    let colour = crate::motion::colour_channels(frame);
    let flat = colour.blur().blur().blur();
    let edges = crate::motion::edge_guide(frame);
    let weave = crate::motion::luminance(&crate::motion::colour_channels(canvas));
    let weave_mean = (weave.data().iter().sum::<f32>() / weave.data().len().max(1) as f32).max(1e-3);
    let (width, height) = (frame.width(), frame.height());
    let mut out = FloatImage::new(width, height, 3);
    for y in 0..height {
        for x in 0..width {
            let base = flat.pixel(x, y);
            let outline = 1.0 - 0.75 * (edges.pixel(x, y)[0] * 1.5).min(1.0);
            let thread = weave.pixel(x % weave.width(), y % weave.height())[0] / weave_mean;
            // Flat tones: the luma rounded to one of five levels, the hue kept.
            let rgb = [base[0], base[1.min(base.len() - 1)], base[2.min(base.len() - 1)]];
            let luma = (0.299 * rgb[0] + 0.587 * rgb[1] + 0.114 * rgb[2]).max(1e-3);
            let tone = ((luma * 5.0).round() / 5.0).max(0.1) / luma;
            let pixel = out.pixel_mut(x, y);
            for c in 0..3 {
                pixel[c] = (rgb[c] * tone * outline * (0.7 + 0.3 * thread)).clamp(0.0, 1.0);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_guide_uses_exactly_the_requested_segments() {
        let guide = map_guide(120, 90, 5, 3);
        let mut seen: Vec<[u32; 3]> =
            guide.data().chunks_exact(3).map(|p| [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()]).collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), 5);
        assert_eq!(map_guide(120, 90, 5, 3), guide);
        let style = crayon_style(&guide, 1);
        assert_eq!((style.width(), style.height(), style.channels()), (120, 90, 3));
    }
}
