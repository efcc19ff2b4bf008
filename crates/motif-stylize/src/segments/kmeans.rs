//! Weighted k-means over a guide's distinct colours ([`crate::Segmentation::KMeans`]): the
//! segment colours of an anti-aliased or compressed guide (§3.6).

use motif_core::SeedStreams;
use motif_core::random::Rng;

/// Weighted k-means over the distinct colours (k-means++ seeding from one seeded stream, then
/// Lloyd iterations until stable); empty clusters are dropped.
pub(super) fn kmeans(unique: &[([u8; 4], usize)], channels: usize, k: usize, seed: u64) -> Vec<Vec<f32>> {
    let points: Vec<Vec<f32>> =
        unique.iter().map(|(key, _)| key[..channels].iter().map(|&v| f32::from(v) / 255.0).collect()).collect();
    let weights: Vec<f64> = unique.iter().map(|&(_, count)| count as f64).collect();
    let distance = |a: &[f32], b: &[f32]| -> f64 { a.iter().zip(b).map(|(x, y)| f64::from((x - y) * (x - y))).sum() };
    if points.len() <= k {
        return points;
    }
    let mut stream = SeedStreams::new(seed).stream("kmeans", 0);
    let mut centres: Vec<Vec<f32>> = Vec::with_capacity(k);
    // k-means++: the heaviest colour first, then colours drawn in proportion to weight × d².
    let heaviest = (0..points.len()).max_by(|&a, &b| weights[a].total_cmp(&weights[b]).then(b.cmp(&a))).unwrap_or(0);
    centres.push(points[heaviest].clone());
    while centres.len() < k {
        let scores: Vec<f64> = points
            .iter()
            .zip(&weights)
            .map(|(p, w)| w * centres.iter().map(|c| distance(p, c)).fold(f64::INFINITY, f64::min))
            .collect();
        let total: f64 = scores.iter().sum();
        if total <= 0.0 {
            break;
        }
        let mut pick = stream.random::<f64>() * total;
        let mut chosen = points.len() - 1;
        for (index, score) in scores.iter().enumerate() {
            if pick < *score {
                chosen = index;
                break;
            }
            pick -= score;
        }
        centres.push(points[chosen].clone());
    }
    let mut assignment = vec![usize::MAX; points.len()];
    for _ in 0..100 {
        let mut changed = false;
        for (index, point) in points.iter().enumerate() {
            let nearest = (0..centres.len())
                .min_by(|&a, &b| distance(point, &centres[a]).total_cmp(&distance(point, &centres[b])))
                .unwrap_or(0);
            if assignment[index] != nearest {
                assignment[index] = nearest;
                changed = true;
            }
        }
        if !changed {
            break;
        }
        let mut sums = vec![vec![0.0_f64; channels]; centres.len()];
        let mut mass = vec![0.0_f64; centres.len()];
        for (index, point) in points.iter().enumerate() {
            mass[assignment[index]] += weights[index];
            for (sum, value) in sums[assignment[index]].iter_mut().zip(point) {
                *sum += weights[index] * f64::from(*value);
            }
        }
        for (centre, (sum, m)) in centres.iter_mut().zip(sums.iter().zip(&mass)) {
            if *m > 0.0 {
                *centre = sum.iter().map(|s| (s / m) as f32).collect();
            }
        }
    }
    let used: Vec<bool> = (0..centres.len()).map(|c| assignment.contains(&c)).collect();
    centres.into_iter().zip(used).filter(|(_, used)| *used).map(|(c, _)| c).collect()
}
